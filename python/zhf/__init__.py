"""zhf: fast rotation of real spherical-harmonic (SH) coefficients.

Convention (docs/conventions.md): real orthonormal SH without the Condon-Shortley phase; the
coefficient of band l, order m is at index l(l+1)+m of the last axis; z up; band 1 is
c (y, z, x). A rotation R is a 3x3 matrix mapping a direction v to R v; rotating f gives the
coefficients of g(w) = f(R^T w). Reflections (det -1) are accepted wherever rotations are.
Other systems' coefficients: convention= (zhf.conventions lists the presets) and zhf.convert.

Arrays: coefficients have shape (..., N*N) for order N (bands 0..N-1), channels being one more
leading axis, e.g. (splats, 3, 16) for RGB at order 4. float32 stays float32, float64 stays
float64, other real dtypes are computed in float64. NaN and infinity are refused (ValueError).
"""

import warnings

import numpy as np

from . import _zhf
from ._zhf import LobeTable, __version__, conventions, isa, isas, use_isa

__all__ = [
    "LobeTable",
    "analyze",
    "band_matrices",
    "conventions",
    "convert",
    "isa",
    "isas",
    "kernels",
    "matrix_from_quaternion",
    "order_of",
    "read_lobe_table",
    "rotate",
    "use_isa",
    "write_lobe_table",
    "__version__",
]

_QUATERNION_ORDERS = ("wxyz", "xyzw")
# A quaternion further than this from unit length is normalised with a warning (the rotation
# check's own tolerance, runtime/tolerances.h kRotationDefect).
_QUATERNION_NOTE = 1e-5


def order_of(coeffs) -> int:
    """The SH order N of an array whose last axis holds N*N coefficients (ValueError otherwise)."""
    n = np.shape(coeffs)[-1] if np.ndim(coeffs) > 0 else 0
    order = int(round(n ** 0.5))
    if n < 1 or order * order != n or order > _zhf.max_order:
        raise ValueError(
            f"coeffs: a last axis of {n} is not N^2 for an order N <= {_zhf.max_order}")
    return order


def kernels(order: int, dtype=np.float64) -> str:
    """The kernels rotate() runs for coefficients of this order and dtype (float32 or float64),
    without a table, on zhf.isa()'s path: "scalar", "lanes", "band_rows", "bands01" or "zxzxz"."""
    if not isinstance(order, (int, np.integer)) or not 1 <= order <= _zhf.max_order:
        raise ValueError(f"order: {order!r} is not an order in 1..{_zhf.max_order}")
    if np.dtype(dtype) not in (np.float32, np.float64):
        raise ValueError(f"dtype: {dtype!r} is not float32 or float64")
    return _zhf.kernels(int(order), np.dtype(dtype) == np.float64)


def matrix_from_quaternion(quaternions, order: str, *, _stacklevel: int = 2) -> np.ndarray:
    """Rotation matrices (..., 3, 3) from quaternions (..., 4).

    order names the component order: "wxyz" (scalar first) or "xyzw" (scalar last). The rotation
    is v -> q v q*, a right-handed turn by 2 acos(w) about (x, y, z); q and -q give the same matrix.
    Non-unit quaternions are normalised (with a warning when off unit length by more than 1e-5);
    a zero or non-finite quaternion raises ValueError.
    """
    if order not in _QUATERNION_ORDERS:
        raise ValueError(f"quaternion_order: {order!r} is not 'wxyz' or 'xyzw'")
    q = _real_array(quaternions, "rotation", np.float64)
    if q.ndim < 1 or q.shape[-1] != 4:
        raise ValueError(f"rotation: quaternions must have shape (..., 4), not {q.shape}")
    matrices, defect = _zhf.matrices_from_quaternions(
        np.ascontiguousarray(q).reshape(-1, 4), order == "wxyz")
    if defect > _QUATERNION_NOTE:
        warnings.warn(f"rotation: quaternions normalised (largest | |q| - 1 | = {defect:.3g})", stacklevel=_stacklevel)
    return matrices.reshape(q.shape[:-1] + (3, 3))


def rotate(coeffs, rotation, *, quaternion_order=None, convention="zhf", table=None, threads: int = 0,
           out=None) -> np.ndarray:
    """Rotated SH coefficients, a new array of the shape (and float dtype) of coeffs, or out.

    coeffs:   (..., N*N), any order N up to 128, on the fastest kernels of the order for this
              machine (zhf.kernels): the generated ones at 2..8, zxzxz above.
    rotation: one rotation for all, (3, 3) or a quaternion (4,), which takes the batch path (band
              matrices built once, then a small dense product per vector); or one per item,
              (..., 3, 3) or (..., 4), broadcast against coeffs.shape[:-1] like NumPy. For
              (..., C, N*N) arrays with one rotation per item give (..., 1, 3, 3).
              Matrices must be orthogonal within 1e-5: rotations, or reflections (det -1).
    quaternion_order: "wxyz" or "xyzw"; required when rotation holds quaternions.
    convention: the coefficients' convention (zhf.conventions), the rotation written in the
              same system's axes: "3dgs" for 3D Gaussian Splatting data, for instance.
    table:    a LobeTable (read_lobe_table) of coeffs' order to rotate with instead of the fastest
              kernels.
    threads:  0 for all cores; large batches are split over them, the GIL released.
    out:      an array to write the result into (C-contiguous, the result's shape and dtype, not
              overlapping coeffs), returned; saves allocating (and first touching) a new one.

    Raises ValueError for a bad shape, a matrix that is not orthogonal, a zero quaternion, an
    unknown convention, or a non-finite coefficient (naming the vector and coefficient).
    """
    c = _real_array(coeffs, "coeffs", None)
    if c.ndim < 1:
        raise ValueError("coeffs: expected an array of shape (..., N*N)")
    order = order_of(c)
    n = order * order
    matrices = _in_zhf_terms(_matrices(rotation, quaternion_order), convention)
    threads = _threads(threads)
    if matrices.shape == (3, 3):
        flat = np.ascontiguousarray(c).reshape(-1, n)
        into = _output(out, c.shape, c, n)
        result = _zhf.rotate_shared(flat, matrices.reshape(9), table, threads, into)
        return out if out is not None else result.reshape(c.shape)
    try:
        batch = np.broadcast_shapes(c.shape[:-1], matrices.shape[:-2])
    except ValueError:
        raise ValueError(
            f"rotation: a batch of shape {matrices.shape[:-2]} does not broadcast against coeffs' "
            f"{c.shape[:-1]} (for one rotation per item of (..., C, N*N) give (..., 1, 3, 3))") from None
    flat = np.ascontiguousarray(np.broadcast_to(c, batch + (n,))).reshape(-1, n)
    flat_r = np.ascontiguousarray(np.broadcast_to(matrices, batch + (3, 3))).reshape(-1, 9)
    into = _output(out, batch + (n,), c, n)
    result = _zhf.rotate_each(flat, flat_r, table, threads, into)
    return out if out is not None else result.reshape(batch + (n,))


def band_matrices(rotation, order: int, *, quaternion_order=None, convention="zhf", table=None) -> list:
    """The dense band matrices D_0..D_{order-1} of one rotation, float64, D_l of shape (2l+1, 2l+1).

    Rotating band l of f is D_l @ f_l, so np.einsum with these is the plain dense way to apply a
    rotation (what zhf.rotate's batch path does in C++).
    """
    if not isinstance(order, (int, np.integer)) or not 1 <= order <= _zhf.max_order:
        raise ValueError(f"order: {order!r} is not an order in 1..{_zhf.max_order}")
    matrices = _in_zhf_terms(_matrices(rotation, quaternion_order), convention)
    if matrices.shape != (3, 3):
        raise ValueError(f"rotation: expected one rotation, not a batch of shape {matrices.shape[:-2]}")
    return _zhf.band_matrices(matrices.reshape(9), int(order), table)


def convert(coeffs, source: str, target: str = "zhf", *, threads: int = 0) -> np.ndarray:
    """Coefficients (..., N*N) in convention source as the same function in convention target.

    Sign patterns are exact (no arithmetic); a change of frame (y-up-rh, y-up-lh) is an exact
    orthogonal transform computed to rounding. See docs/conventions.md for each preset.
    """
    m = np.asarray(_zhf.conversion(source, target)).reshape(3, 3)
    return rotate(coeffs, m, threads=threads)


def analyze(coeffs, tolerance: float = _zhf.default_zonal_fit) -> dict:
    """What SH data needs, as `zhf analyze` reports it: coeffs (..., N*N), every vector counted.

    Returns order, band_energy (per band, summed), truncation_error (relative L2 error of keeping
    bands 0..K-1, for K = 1..N), smallest_order (the smallest K within tolerance) and zero_bands
    (bands below it that can be dropped within the remaining budget).
    """
    c = _real_array(coeffs, "coeffs", np.float64)
    if c.ndim < 1:
        raise ValueError("coeffs: expected an array of shape (..., N*N)")
    order = order_of(c)
    return _zhf.analyze(np.ascontiguousarray(c).reshape(-1, order * order), float(tolerance))


def read_lobe_table(path, order: int = 0) -> LobeTable:
    """A lobe table file (docs/formats.md), fully validated; order > 0 also checks its order."""
    return _zhf.read_lobe_table(str(path), int(order))


def write_lobe_table(table: LobeTable, path) -> None:
    """Writes the table as zhf writes it (validated first; the file replaced whole or not at all)."""
    _zhf.write_lobe_table(table, str(path))


def _real_array(value, name, dtype):
    """value as an ndarray without copying when it already is one: float32/float64 kept (or
    dtype), other real numbers as float64; anything else refused."""
    array = np.asarray(value)
    if array.dtype.kind not in "biuf":
        raise ValueError(f"{name}: dtype {array.dtype} is not real numbers")
    if dtype is not None:
        return array.astype(dtype, copy=False)
    if array.dtype not in (np.float32, np.float64):
        return array.astype(np.float64)
    return array


def _output(out, shape, coeffs, n):
    """out as a (count, n) view to write into, or None; refused unless it can take the result."""
    if out is None:
        return None
    if not isinstance(out, np.ndarray):
        raise ValueError(f"out: expected a numpy array, not {type(out).__name__}")
    dtype = coeffs.dtype
    if out.shape != shape or out.dtype != dtype:
        raise ValueError(f"out: expected shape {shape} and dtype {dtype}, not {out.shape} and {out.dtype}")
    if not out.flags.c_contiguous or not out.flags.writeable:
        raise ValueError("out: must be C-contiguous and writeable")
    if np.may_share_memory(out, coeffs):
        raise ValueError("out: overlaps coeffs (rotation in place is not supported)")
    return out.reshape(-1, n)


def _matrices(rotation, quaternion_order):
    r = _real_array(rotation, "rotation", np.float64)
    if r.ndim >= 2 and r.shape[-2:] == (3, 3):
        if quaternion_order is not None:
            raise ValueError("quaternion_order: given, but rotation holds 3x3 matrices")
        return r
    if r.ndim >= 1 and r.shape[-1] == 4:
        if quaternion_order is None:
            raise ValueError("rotation: quaternions (..., 4) need quaternion_order='wxyz' or 'xyzw'")
        return matrix_from_quaternion(r, quaternion_order, _stacklevel=4)
    raise ValueError(f"rotation: expected matrices (..., 3, 3) or quaternions (..., 4), not shape {r.shape}")


def _in_zhf_terms(matrices, convention):
    if convention == "zhf":
        return matrices
    if not isinstance(convention, str):
        raise ValueError(f"convention: {convention!r} is not a name ({', '.join(conventions)})")
    flat = np.ascontiguousarray(matrices).reshape(-1, 9)
    return _zhf.rotations_in_zhf_terms(convention, flat).reshape(matrices.shape)


def _threads(threads):
    if not isinstance(threads, (int, np.integer)) or threads < 0 or threads > _zhf.max_threads:
        raise ValueError(f"threads: {threads!r} is not a count in 0..{_zhf.max_threads} (0: all cores)")
    return int(threads)


