"""zhf.rotate and its rotation forms, against independent references (reference.py)."""

import numpy as np
import pytest

import zhf
from zhf import _zhf

from reference import random_directions, random_rotation, real_sh, rotation_about_axis

TOL = _zhf.tolerances
ORDERS = list(range(1, 14)) + [16, 33]


def unit_vectors(rng, shape):
    f = rng.standard_normal(shape)
    return f / np.linalg.norm(f, axis=-1, keepdims=True)


@pytest.mark.parametrize("order", ORDERS)
def test_rotated_coefficients_are_the_rotated_function(order):
    # g(w) = f(R^T w) at random directions, with SH evaluated independently of zhf.
    rng = np.random.default_rng(order)
    f = unit_vectors(rng, (4, order * order))
    r = random_rotation(rng)
    g = zhf.rotate(f, r)
    w = random_directions(rng, 40)
    g_at_w = g @ real_sh(order, w).T
    f_at_rtw = f @ real_sh(order, w @ r).T  # rows of w @ r are R^T w
    error = np.abs(g_at_w - f_at_rtw).max()
    # A coefficient error e moves the value by at most e sqrt(N^2 / 4 pi).
    assert error <= TOL["pointwise"] * max(1.0, order / np.sqrt(4 * np.pi)), f"order {order}: {error:.3g}"


@pytest.mark.parametrize("order", [2, 8, 9, 16, 128])
def test_every_order_runs_zhf_dispatch_and_names_its_kernels(order):
    # Without a table every order takes zhf::dispatch's kernels (no lobe tables are shipped):
    # the generated ones up to 8, zxzxz above (in float through the band rows where they hold).
    for dtype in (np.float32, np.float64):
        kernels = zhf.kernels(order, dtype)
        if order <= 8:
            assert kernels in ("scalar", "lanes", "band_rows", "bands01"), f"order {order}, {dtype}: {kernels}"
        else:
            assert kernels in (("zxzxz", "band_rows") if dtype == np.float32 else ("zxzxz",)), f"order {order}: {kernels}"
    f = np.zeros(order * order)
    f[0] = 1
    np.testing.assert_allclose(zhf.rotate(f, random_rotation(np.random.default_rng(order))), f, atol=TOL["double"])


@pytest.mark.parametrize("order", range(2, 9))
def test_float32_within_the_float_target(order):
    rng = np.random.default_rng(100 + order)
    f = unit_vectors(rng, (64, order * order))
    r = random_rotation(rng)
    expected = zhf.rotate(f, r)
    got = zhf.rotate(f.astype(np.float32), r.astype(np.float32))
    assert got.dtype == np.float32
    error = np.abs(got.astype(np.float64) - expected)
    worst = np.unravel_index(error.argmax(), error.shape)
    assert error.max() <= TOL["float_rotation"], f"order {order}, vector {worst[0]}, index {worst[1]}: {error.max():.3g}"


def test_shapes_dtypes_and_broadcasting():
    rng = np.random.default_rng(7)
    f = rng.standard_normal((5, 3, 16))
    rs = np.stack([random_rotation(rng) for _ in range(5)])
    one = zhf.rotate(f, rs[0])
    assert one.shape == f.shape and one.dtype == np.float64
    # One rotation per item, shared by the channels, against a loop.
    per_item = zhf.rotate(f, rs[:, None])
    for i in range(5):
        np.testing.assert_allclose(per_item[i], zhf.rotate(f[i], rs[i]), atol=TOL["double"], rtol=0)
    # One vector, many rotations: the output takes the broadcast shape.
    many = zhf.rotate(f[0, 0], rs)
    assert many.shape == (5, 16)
    # Integers are computed in float64; the input is never changed.
    ints = np.arange(16)
    before = ints.copy()
    assert zhf.rotate(ints, rs[0]).dtype == np.float64
    np.testing.assert_array_equal(ints, before)
    # Empty batches and order 1 (a copy).
    assert zhf.rotate(np.zeros((0, 9)), rs[0]).shape == (0, 9)
    np.testing.assert_array_equal(zhf.rotate([[2.5], [1.0]], rs[0]), [[2.5], [1.0]])


def test_batch_path_within_the_float_target():
    # Above N^2 vectors one rotation takes the dense batch path (band matrices built by the float
    # kernels); below, the kernels one by one. Both against the float64 result.
    rng = np.random.default_rng(8)
    r = random_rotation(rng)
    for count in (5000, 5):
        f = unit_vectors(rng, (count, 3, 16))
        error = np.abs(zhf.rotate(f.astype(np.float32), r).astype(np.float64) - zhf.rotate(f, r)).max()
        assert error <= TOL["float_rotation"], f"order 4, {count} vectors: {error:.3g}"


def test_out_receives_the_result():
    rng = np.random.default_rng(12)
    f = rng.standard_normal((3000, 3, 16)).astype(np.float32)
    rs = np.stack([random_rotation(rng) for _ in range(3000)])[:, None]
    for r in (rs[0, 0], rs):
        out = np.empty_like(f)
        assert zhf.rotate(f, r, out=out) is out
        np.testing.assert_array_equal(out, zhf.rotate(f, r))
    for bad, message in [
        (np.empty((3000, 3, 16)), "out: expected shape"),
        (np.empty((3000, 3, 9), dtype=np.float32), "out: expected shape"),
        (np.empty((3, 3000, 16), dtype=np.float32).transpose(1, 0, 2), "C-contiguous"),
        (f, "overlaps coeffs"),
        ([0.0] * 16, "expected a numpy array"),
    ]:
        with pytest.raises(ValueError, match=message):
            zhf.rotate(f, rs[0, 0], out=bad)


def test_thread_count_never_changes_the_result():
    rng = np.random.default_rng(9)
    f = rng.standard_normal((20000, 25)).astype(np.float32)
    rs = np.stack([random_rotation(rng) for _ in range(20000)])
    np.testing.assert_array_equal(zhf.rotate(f, rs, threads=1), zhf.rotate(f, rs, threads=2))
    np.testing.assert_array_equal(zhf.rotate(f, rs[0], threads=1), zhf.rotate(f, rs[0], threads=2))


def test_quaternions_in_both_orders_match_axis_angle():
    rng = np.random.default_rng(10)
    for _ in range(20):
        axis = rng.standard_normal(3)
        angle = rng.uniform(-np.pi, np.pi)
        u = axis / np.linalg.norm(axis)
        wxyz = np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * u])
        xyzw = np.roll(wxyz, -1)
        expected = rotation_about_axis(axis, angle)
        np.testing.assert_allclose(zhf.matrix_from_quaternion(wxyz, "wxyz"), expected, atol=1e-15)
        np.testing.assert_allclose(zhf.matrix_from_quaternion(xyzw, "xyzw"), expected, atol=1e-15)
        np.testing.assert_allclose(zhf.matrix_from_quaternion(-wxyz, "wxyz"), expected, atol=1e-15)
    f = rng.standard_normal((3, 16))
    np.testing.assert_allclose(zhf.rotate(f, wxyz, quaternion_order="wxyz"), zhf.rotate(f, expected), atol=TOL["double"])
    batch = np.stack([wxyz, -wxyz, wxyz])
    np.testing.assert_allclose(zhf.rotate(f, batch, quaternion_order="wxyz"), zhf.rotate(f, expected), atol=TOL["double"])


def test_non_unit_quaternions_are_normalised_with_a_warning():
    q = np.array([2.0, 0.0, 0.0, 2.0])  # a quarter turn about z, length 2*sqrt(2)
    with pytest.warns(UserWarning, match="normalised"):
        r = zhf.matrix_from_quaternion(q, "wxyz")
    np.testing.assert_allclose(r, rotation_about_axis([0, 0, 1], np.pi / 2), atol=1e-15)


def test_reflections_and_exact_axis_maps():
    rng = np.random.default_rng(13)
    f = unit_vectors(rng, (6, 25))
    mirror = np.diag([1.0, 1.0, -1.0])  # z -> -z: coefficient (l, m) times (-1)^(l+m), bit for bit
    signs = np.array([(-1.0) ** (l + m) for l in range(5) for m in range(-l, l + 1)])
    np.testing.assert_array_equal(zhf.rotate(f, mirror), f * signs)
    np.testing.assert_array_equal(zhf.rotate(np.tile(f, (10, 1)), mirror), np.tile(f * signs, (10, 1)))
    # A general reflection, one rotation and one per item, as a function.
    q = -random_rotation(rng)
    w = random_directions(rng, 30)
    for g in (zhf.rotate(f, q), zhf.rotate(f, np.broadcast_to(q, (6, 3, 3)))):
        error = np.abs(g @ real_sh(5, w).T - f @ real_sh(5, w @ q).T).max()
        assert error <= TOL["pointwise"], f"order 5 reflection: {error:.3g}"


def test_conventions_convert_and_rotate_in_their_own_terms():
    rng = np.random.default_rng(14)
    f = unit_vectors(rng, (4, 16))
    assert zhf.conventions[:3] == ["zhf", "condon-shortley", "3dgs"]
    # 3DGS is the Condon-Shortley sign pattern: (-1)^m, exactly.
    cs = np.array([(-1.0) ** abs(m) for l in range(4) for m in range(-l, l + 1)])
    np.testing.assert_array_equal(zhf.convert(f, "3dgs"), f * cs)
    r = random_rotation(rng)
    np.testing.assert_allclose(zhf.rotate(f, r, convention="3dgs"), zhf.rotate(f * cs, r) * cs, atol=TOL["double"], rtol=0)
    # Round trips through a frame change.
    for name in zhf.conventions:
        np.testing.assert_allclose(zhf.convert(zhf.convert(f, name), "zhf", name), f, atol=TOL["double"], rtol=0)


def test_objects_with_array_interface_work():
    class Wrapped:
        def __init__(self, a):
            self.a = a

        def __array__(self, dtype=None):
            return self.a

    f = np.random.default_rng(11).standard_normal((2, 9)).astype(np.float32)
    r = rotation_about_axis([1, 2, 3], 0.4)
    np.testing.assert_array_equal(zhf.rotate(Wrapped(f), Wrapped(r)), zhf.rotate(f, r))
    np.testing.assert_array_equal(zhf.rotate(memoryview(f), r), zhf.rotate(f, r))


def test_torch_tensors_through_numpy():
    torch = pytest.importorskip("torch")
    f = torch.randn(4, 3, 16)
    r = rotation_about_axis([0, 1, 0], 1.0)
    got = zhf.rotate(f, r)  # through the tensor's __array__
    assert got.dtype == np.float32
    np.testing.assert_array_equal(got, zhf.rotate(f.numpy(), r))


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: zhf.rotate(np.full(16, np.nan), np.eye(3)), "coeffs: vector 0, coefficient 0: nan is not finite"),
        (lambda: zhf.rotate(np.r_[np.zeros(20), np.inf, np.zeros(11)].reshape(2, 16), np.eye(3)),
         "coeffs: vector 1, coefficient 4: inf is not finite"),
        (lambda: zhf.rotate(np.zeros(15), np.eye(3)), "coeffs: a last axis of 15 is not N^2"),
        (lambda: zhf.rotate(np.zeros(16), np.eye(3), convention="y-down"), "convention: 'y-down' is not one of zhf"),
        (lambda: zhf.rotate(np.zeros(16), 1.1 * np.eye(3)), "rotation: rotation matrix is not orthonormal"),
        (lambda: zhf.rotate(np.zeros(16), np.array([np.eye(3), np.diag([1, -1, -1]), 2 * np.eye(3)])),
         "rotation 2: rotation matrix is not orthonormal"),
        (lambda: zhf.rotate(np.zeros(16), [[np.nan] * 3] * 3), "rotation: rotation matrix has a non-finite entry"),
        (lambda: zhf.rotate(np.zeros(16), [1, 0, 0, 0]), "quaternion_order='wxyz' or 'xyzw'"),
        (lambda: zhf.rotate(np.zeros(16), [0, 0, 0, 0], quaternion_order="wxyz"), "quaternion 0 is zero"),
        (lambda: zhf.rotate(np.zeros(16), [1, 0, 0, 0], quaternion_order="zyxw"), "quaternion_order: 'zyxw'"),
        (lambda: zhf.rotate(np.zeros(16), np.eye(3), quaternion_order="wxyz"), "quaternion_order: given"),
        (lambda: zhf.rotate(np.zeros(16), np.eye(2)), "rotation: expected matrices"),
        (lambda: zhf.rotate(np.zeros((4, 16)), np.stack([np.eye(3)] * 3)), "does not broadcast"),
        (lambda: zhf.rotate(np.zeros(16, dtype=complex), np.eye(3)), "coeffs: dtype complex128"),
        (lambda: zhf.rotate(np.zeros(129 * 129), np.eye(3)), "is not N^2 for an order N <= 128"),
        (lambda: zhf.rotate(np.zeros(16), np.eye(3), threads=-1), "threads: -1"),
        (lambda: zhf.rotate(np.float64(1.0), np.eye(3)), "coeffs: expected an array"),
    ],
)
def test_bad_input_is_a_value_error_naming_the_field(call, message):
    with pytest.raises(ValueError) as raised:
        call()
    assert message in str(raised.value)
    assert "\n" not in str(raised.value)


def test_every_isa_path_the_cpu_runs_rotates_alike():
    # Each path this CPU runs, forced in turn, against the double reference (real_sh), and the
    # path picked first restored; a path it lacks or an unknown name refused in one line.
    picked = zhf.isa()
    assert picked == zhf.isas()[0]
    rng = np.random.default_rng(54)
    try:
        for name in zhf.isas():
            zhf.use_isa(name)
            assert zhf.isa() == name
            for order in (2, 4, 5, 8):
                f = unit_vectors(rng, (300, order * order))
                rotations = np.stack([random_rotation(rng) for _ in range(300)])
                w = random_directions(rng, 20)
                for dtype, tol in ((np.float64, TOL["pointwise"]), (np.float32, 10 * TOL["float_rotation"])):
                    g = zhf.rotate(f.astype(dtype), rotations.astype(dtype), threads=1)
                    g_at_w = np.einsum("vi,di->vd", g.astype(np.float64), real_sh(order, w))
                    rtw = np.einsum("dj,vjk->vdk", w, rotations)  # rows R^T w per vector
                    f_at_rtw = np.stack([f[v] @ real_sh(order, rtw[v]).T for v in range(len(f))])
                    error = np.abs(g_at_w - f_at_rtw).max()
                    assert error <= tol * order, f"{name}, order {order}, {dtype.__name__}: {error:.3g}"
    finally:
        zhf.use_isa(picked)
    for bad in ("sse9", "avx1024"):
        with pytest.raises(ValueError, match="is not one of this build's paths"):
            zhf.use_isa(bad)
    assert zhf.isa() == picked
