"""Per-vector rotations from Python at round counts (powers of two) against counts just below:
a layout whose streams sit a power of two apart would share cache sets and show a cliff there.

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/python_round_counts.py [--runs 7]

zhf.rotate with one rotation per vector (float32, threads=1, out= a reused array); prints the best
time per vector over the runs, each run 20 calls, and the ratio of each round count to the count
below it.
"""

import argparse
import time

import numpy as np

import zhf

COUNTS = ((4096, 4000), (65536, 65000))


def random_rotations(rng, count):
    q = rng.normal(size=(count, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    return zhf.matrix_from_quaternion(q, "wxyz").astype(np.float32)


def ns_per_vector(order, count, runs, rng):
    coeffs = rng.normal(size=(count, order * order)).astype(np.float32)
    rotations = random_rotations(rng, count)
    out = np.empty_like(coeffs)
    best = float("inf")
    for _ in range(runs):
        start = time.perf_counter()
        for _ in range(20):
            zhf.rotate(coeffs, rotations, threads=1, out=out)
        best = min(best, (time.perf_counter() - start) / 20)
    return best / count * 1e9


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    args = parser.parse_args()
    rng = np.random.default_rng(1)
    print(f"zhf {zhf.__version__}, path {zhf.isa()}")
    print("| order | " + " | ".join(f"{a}: ns per vector | {b} | {a} / {b}" for a, b in COUNTS) + " |")
    print("| --- |" + " --- | --- | --- |" * len(COUNTS))
    for order in (3, 4, 6, 8):
        cells = []
        for round_count, below in COUNTS:
            a = ns_per_vector(order, round_count, args.runs, rng)
            b = ns_per_vector(order, below, args.runs, rng)
            cells += [f"{a:.1f}", f"{b:.1f}", f"{a / b:.2f}"]
        print(f"| {order} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
