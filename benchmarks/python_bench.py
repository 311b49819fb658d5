"""Rotating many degree-3 RGB SH vectors under one rotation from Python, against the C++ batch
path and the dense ways a NumPy or PyTorch user would write it, all in one run.

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/python_bench.py [--vectors 1000000] [--runs 7]

Prints a Markdown table: median seconds per call, throughput in vectors (of 3 x 16 floats) per
second, the ratio to the C++ batch path into a reused buffer, and each method's largest difference
from zhf.rotate. zhf.rotate returning a new array compares with the C++ path into a new buffer
(both pay the first touch of 192 MB of fresh pages); with out= it compares with the reused one.
"""

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import zhf

ORDER, CHANNELS = 4, 3


def median_seconds(call, runs):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vectors", type=int, default=1_000_000)
    parser.add_argument("--runs", type=int, default=7)
    default_cpp = Path(__file__).resolve().parents[1] / "build" / "bench" / "zhf_shared_rotation_bench"
    parser.add_argument("--cpp", default=str(default_cpp), help="the C++ batch-path program")
    args = parser.parse_args()

    rng = np.random.default_rng(1)
    f = rng.standard_normal((args.vectors, CHANNELS, ORDER * ORDER)).astype(np.float32)
    r = zhf.matrix_from_quaternion([0.8, 0.2, 0.4, 0.4], "wxyz")
    expected = zhf.rotate(f, r)
    bands = [d.astype(np.float32) for d in zhf.band_matrices(r, ORDER)]
    block = np.zeros((ORDER * ORDER, ORDER * ORDER), dtype=np.float32)
    for l, d in enumerate(bands):
        block[l * l : (l + 1) ** 2, l * l : (l + 1) ** 2] = d
    out = np.empty_like(f)

    def einsum_per_band():
        g = np.empty_like(f)
        for l, d in enumerate(bands):
            g[..., l * l : (l + 1) ** 2] = np.einsum("ij,...j->...i", d, f[..., l * l : (l + 1) ** 2])
        return g

    methods = [
        ("zhf.rotate (new array)", lambda: zhf.rotate(f, r)),
        ("zhf.rotate (out=)", lambda: zhf.rotate(f, r, out=out)),
        ("zhf.rotate (out=, threads=1)", lambda: zhf.rotate(f, r, out=out, threads=1)),
        ("NumPy einsum per band", einsum_per_band),
        ("NumPy matmul, block-diagonal 16x16", lambda: f @ block.T),
    ]
    try:
        import torch

        tf, tblock = torch.from_numpy(f), torch.from_numpy(block)
        methods.append((f"torch {torch.__version__} matmul, block-diagonal (e3nn-style)", lambda: (tf @ tblock.T).numpy()))
        methods.append(("torch einsum, block-diagonal", lambda: torch.einsum("ij,...j->...i", tblock, tf).numpy()))
    except ImportError:
        pass

    def cpp_seconds(fresh):
        # The C++ batch path in its own process on the same machine, same sizes.
        run = subprocess.run([args.cpp, str(ORDER), str(args.vectors), str(CHANNELS), str(args.runs), "0", str(fresh)],
                             check=True, capture_output=True, text=True)
        return json.loads(run.stdout)["median_s"]

    reused, fresh = cpp_seconds(0), cpp_seconds(1)
    rows = [("C++ Rotator::rotate_shared into a reused buffer", reused, 0.0),
            ("C++ Rotator::rotate_shared into a new buffer", fresh, 0.0)]
    for name, call in methods:
        got = np.asarray(call())
        difference = float(np.abs(got.reshape(expected.shape) - expected).max())
        rows.append((name, median_seconds(call, args.runs), difference))

    print(f"{args.vectors} vectors x {CHANNELS} channels x {ORDER * ORDER} float32, one rotation; "
          f"median of {args.runs}; {os.cpu_count()} cores; numpy {np.__version__}; Python {sys.version.split()[0]}")
    print()
    print("| method | median s | vectors/s | time vs C++, reused buffer | max diff vs zhf.rotate |")
    print("| --- | --- | --- | --- | --- |")
    for name, seconds, difference in rows:
        print(f"| {name} | {seconds:.4f} | {args.vectors / seconds:.3g} | {seconds / reused:.2f}x | {difference:.2g} |")


if __name__ == "__main__":
    main()
