"""Lobe tables, band matrices and analysis from Python."""

from pathlib import Path

import numpy as np
import pytest

import zhf
from zhf import _zhf

from reference import random_rotation

TOL = _zhf.tolerances
TABLES = Path(__file__).resolve().parents[2] / "generated" / "lobes"  # the checked-in ones


def test_a_table_reads_writes_and_rotates(tmp_path):
    table = zhf.read_lobe_table(TABLES / "order_9.json", order=9)
    assert table.order == 9 and table.directions.shape == (17, 3)
    assert [b["l"] for b in table.bands] == list(range(2, 9))
    np.testing.assert_allclose(np.linalg.norm(table.directions, axis=1), 1, atol=1e-15)
    copy = tmp_path / "order_9.json"
    zhf.write_lobe_table(table, copy)
    assert copy.read_bytes() == (TABLES / "order_9.json").read_bytes()
    # A table given rotates as the tableless path does, within the double tolerance: at order 3,
    # where the table's rotation (its lobes with AVX2, zxzxz without) is another method than the
    # generated kernel the tableless path runs.
    f = np.random.default_rng(1).standard_normal((3, 9))
    f /= np.linalg.norm(f, axis=1, keepdims=True)  # unit inputs, as the tolerance is stated for
    r = random_rotation(np.random.default_rng(2))
    three = zhf.read_lobe_table(TABLES / "order_3.json", order=3)
    np.testing.assert_allclose(zhf.rotate(f, r, table=three), zhf.rotate(f, r), atol=TOL["double"])


def test_a_table_of_another_order_is_refused():
    table = zhf.read_lobe_table(TABLES / "order_10.json")
    with pytest.raises(ValueError, match="table: order 10, but the rotation's is 9"):
        zhf.rotate(np.zeros(81), np.eye(3), table=table)


def test_bad_table_files_are_refused(tmp_path):
    broken = tmp_path / "order_9.json"
    broken.write_text('{"format": "zhf-lobes-1", "order": 9')
    with pytest.raises(ValueError, match="order_9.json"):
        zhf.read_lobe_table(broken)
    with pytest.raises(ValueError, match="order"):
        zhf.read_lobe_table(TABLES / "order_9.json", order=10)
    with pytest.raises(OSError):
        zhf.write_lobe_table(zhf.read_lobe_table(TABLES / "order_9.json"), tmp_path)


@pytest.mark.parametrize("order", [1, 4, 9])
def test_band_matrices_are_orthogonal_and_rotate(order):
    rng = np.random.default_rng(order)
    r = random_rotation(rng)
    bands = zhf.band_matrices(r, order)
    assert [b.shape for b in bands] == [(2 * l + 1, 2 * l + 1) for l in range(order)]
    for l, d in enumerate(bands):
        error = np.abs(d @ d.T - np.eye(2 * l + 1)).max()
        assert error <= TOL["double"], f"order {order}, band {l}: |D D^T - I| = {error:.3g}"
    f = rng.standard_normal((7, order * order))
    dense = np.concatenate([f[:, l * l : (l + 1) ** 2] @ d.T for l, d in enumerate(bands)], axis=1)
    np.testing.assert_allclose(dense, zhf.rotate(f, r), atol=TOL["double"], rtol=0)


def test_analyze_finds_the_order_the_data_needs():
    rng = np.random.default_rng(3)
    f = np.zeros((10, 3, 25))
    f[..., :9] = rng.standard_normal((10, 3, 9))  # bands 0..2 only
    report = zhf.analyze(f)
    assert report["order"] == 5
    assert report["smallest_order"] == 3
    assert report["band_energy"][3] == 0 and report["band_energy"][4] == 0
    with pytest.raises(ValueError, match="tolerance"):
        zhf.analyze(f, tolerance=2.0)
    with pytest.raises(ValueError, match="not finite"):
        zhf.analyze(np.full(4, np.nan))
