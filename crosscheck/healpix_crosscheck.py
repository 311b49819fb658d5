"""zhf's HEALPix path against healpy on the same maps: projection (zhf project --healpix) against
the known coefficients and against healpy's map2alm, power spectra against anafast, a masked map,
and maps written by zhf (zhf needlets synthesize --out) read by healpy. Prints a Markdown
table (docs/frames.md).

    /usr/bin/python3 crosscheck/healpix_crosscheck.py ZHF [--nside 64] [--order 33] [--seed 1]

ZHF: the zhf binary. Needs Debian's python3-healpy (apt-get install python3-healpy). The test map
is made here: random real coefficients of bands < ORDER (power ~ 1/(l+1)^2), turned into healpy's
complex a_lm by the conversion below (written independently of zhf's C++), synthesised by healpy.

zhf's real SH have no Condon-Shortley phase; healpy's complex Y_lm have it. For m > 0:
  a_lm = (-1)^m (f_{l,m} - i f_{l,-m}) / sqrt(2),   a_l0 = f_l0.
"""

import argparse
import json
import subprocess
import tempfile
import time
from pathlib import Path

import healpy as hp
import numpy as np


def real_to_healpy(f, order):
    alm = np.zeros(hp.Alm.getsize(order - 1), dtype=np.complex128)
    for l in range(order):
        alm[hp.Alm.getidx(order - 1, l, 0)] = f[l * (l + 1)]
        for m in range(1, l + 1):
            alm[hp.Alm.getidx(order - 1, l, m)] = (-1) ** m * (f[l * (l + 1) + m] - 1j * f[l * (l + 1) - m]) / np.sqrt(2)
    return alm


def healpy_to_real(alm, order):
    lmax = hp.Alm.getlmax(len(alm))
    f = np.zeros(order * order)
    for l in range(order):
        f[l * (l + 1)] = alm[hp.Alm.getidx(lmax, l, 0)].real
        for m in range(1, l + 1):
            a = alm[hp.Alm.getidx(lmax, l, m)]
            f[l * (l + 1) + m] = (-1) ** m * np.sqrt(2) * a.real
            f[l * (l + 1) - m] = -((-1) ** m) * np.sqrt(2) * a.imag
    return f


def spectrum(f, order):
    return np.array([np.sum(f[l * l:(l + 1) * (l + 1)] ** 2) / (2 * l + 1) for l in range(order)])


def run(zhf, *args):
    start = time.perf_counter()
    subprocess.run([zhf, *args], check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def zhf_project(zhf, work, map_path, order, iterations, mask=None):
    out = work / "c.json"
    args = ["project", "--healpix", str(map_path), "--order", str(order), "--iterations", str(iterations), "--out", str(out)]
    if mask is not None:
        args += ["--mask", str(mask)]
    seconds = run(zhf, *args)
    return np.array(json.loads(out.read_text())[0]), seconds


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("zhf")
    parser.add_argument("--nside", type=int, default=64)
    parser.add_argument("--order", type=int, default=33)
    parser.add_argument("--seed", type=int, default=1)
    a = parser.parse_args()
    order, nside = a.order, a.nside
    rng = np.random.default_rng(a.seed)
    known = rng.standard_normal(order * order)
    for l in range(order):
        known[l * l:(l + 1) * (l + 1)] /= l + 1
    alm = real_to_healpy(known, order)
    sky = hp.alm2map(alm, nside, lmax=order - 1)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        ring, nested = work / "ring.fits", work / "nested.fits"
        hp.write_map(str(ring), sky, dtype=np.float64, overwrite=True)
        hp.write_map(str(nested), hp.reorder(sky, r2n=True), nest=True, dtype=np.float64, overwrite=True)
        for iterations in (0, 3):
            for path, name in ((ring, "RING"), (nested, "NESTED")):
                f, seconds = zhf_project(a.zhf, work, path, order, iterations)
                start = time.perf_counter()
                theirs = healpy_to_real(hp.map2alm(sky, lmax=order - 1, iter=iterations, use_weights=False), order)
                healpy_seconds = time.perf_counter() - start
                cl = hp.anafast(sky, lmax=order - 1, iter=iterations, use_weights=False)
                rows.append((f"band-limited, {name}, iter {iterations}", np.abs(f - known).max(), np.abs(f - theirs).max(),
                             np.max(np.abs(spectrum(f, order) - cl) / cl), seconds, healpy_seconds))
        # A galactic-cut style mask: 20 degrees either side of the equator, UNSEEN in the map there.
        theta, _ = hp.pix2ang(nside, np.arange(hp.nside2npix(nside)))
        mask = (np.abs(np.pi / 2 - theta) >= np.radians(20)).astype(np.float64)
        cut = np.where(mask > 0, sky, hp.UNSEEN)
        cut_path, mask_path = work / "cut.fits", work / "mask.fits"
        hp.write_map(str(cut_path), cut, dtype=np.float64, overwrite=True)
        hp.write_map(str(mask_path), mask, dtype=np.float64, overwrite=True)
        f, seconds = zhf_project(a.zhf, work, cut_path, order, 3, mask_path)
        start = time.perf_counter()
        theirs = healpy_to_real(hp.map2alm(sky * mask, lmax=order - 1, iter=3, use_weights=False), order)
        healpy_seconds = time.perf_counter() - start
        cl = hp.anafast(sky * mask, lmax=order - 1, iter=3, use_weights=False)
        rows.append(("masked (20-degree galactic cut), iter 3", float("nan"), np.abs(f - theirs).max(),
                     np.max(np.abs(spectrum(f, order) - cl) / cl), seconds, healpy_seconds))
        # Maps zhf writes, read by healpy: the needlet round trip of the full map (a tight frame on
        # bands < ORDER) against healpy's synthesis of the known coefficients.
        beta = work / "beta.json"
        run(a.zhf, "needlets", "analyze", "--healpix", str(ring), "--order", str(order), "--out", str(beta))
        written = []
        for ordering in ("ring", "nested"):
            out = work / f"out_{ordering}.fits"
            run(a.zhf, "needlets", "synthesize", "--in", str(beta), "--out", str(out), "--nside", str(nside), "--ordering", ordering)
            back = hp.read_map(str(out), nest=None, dtype=np.float64)
            if ordering == "nested":
                back = hp.reorder(back, n2r=True)
            written.append(np.abs(back - sky).max())
    print(f"HEALPix Nside {nside}, bands 0..{order - 1}; healpy {hp.__version__}; map2alm without ring weights (use_weights=False)\n")
    print("| map | max error vs known coefficients | max difference vs healpy map2alm | max relative difference vs anafast C_l | zhf s | healpy s |")
    print("|---|---|---|---|---|---|")
    for name, known_error, healpy_error, cl_error, seconds, healpy_seconds in rows:
        shown = "-" if np.isnan(known_error) else f"{known_error:.2e}"
        print(f"| {name} | {shown} | {healpy_error:.2e} | {cl_error:.2e} | {seconds:.3f} | {healpy_seconds:.3f} |")
    print(f"\nzhf needlets analyze -> synthesize --out, read by healpy.read_map: max |map - healpy alm2map| "
          f"RING {written[0]:.2e}, NESTED {written[1]:.2e}")


if __name__ == "__main__":
    main()
