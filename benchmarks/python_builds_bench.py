"""The Python module of two builds on the same workloads, paired call by call: as a user gets it
(no -march: the compiled library picks its path at run time) against one built with
-DCMAKE_CXX_FLAGS=-march=x86-64-v3, or any other pair.

    /usr/bin/python3 benchmarks/python_builds_bench.py build/python /tmp/build-v3/python [--reps 15]

Each argument is a PYTHONPATH holding a built `zhf`. Two builds of one extension cannot share an
interpreter (pybind11 registers its types once per process), so each runs in a child interpreter
of its own that stays up and times one call when asked. Workloads, float32, threads=1, into a
reused output: at orders 4, 6 and 8, 200 000 vectors each under its own rotation and 1 000 000
vectors under one rotation. Each repetition times the first build's call then the second's (the
order swapped every other repetition), after one warm-up call of each. The table gives each
build's median ns per vector and the median of the per-repetition ratios second / first. The
inputs are the same for both (fixed seeds).
"""

import argparse
import os
import subprocess
import sys
import time

import numpy as np

ORDERS = (4, 6, 8)
EACH, SHARED = 200_000, 1_000_000


def names():
    """(name, vectors) of every workload, in the order workloads() makes them."""
    out = []
    for order in ORDERS:
        out.append((f"order {order}, {EACH:,} vectors, one rotation each", EACH))
        out.append((f"order {order}, {SHARED:,} vectors, one rotation", SHARED))
    return out


def workloads():
    """One call per workload (in names()' order), inputs drawn from a fixed seed."""
    import zhf

    rng = np.random.default_rng(7)
    out = []
    for order in ORDERS:
        n = order * order
        q = rng.standard_normal((EACH, 4))
        matrices = zhf.matrix_from_quaternion(q / np.linalg.norm(q, axis=1, keepdims=True), "wxyz").astype(np.float32)
        each = rng.standard_normal((EACH, n)).astype(np.float32)
        shared = rng.standard_normal((SHARED, n)).astype(np.float32)
        out_each, out_shared = np.empty_like(each), np.empty_like(shared)
        out.append(lambda e=each, m=matrices, o=out_each: zhf.rotate(e, m, threads=1, out=o))
        out.append(lambda s=shared, m=matrices[0], o=out_shared: zhf.rotate(s, m, threads=1, out=o))
    return out


def child():
    """Reads workload numbers from stdin; answers each with the seconds one call took."""
    import zhf

    cases = workloads()
    print(zhf.isa(), flush=True)
    for line in sys.stdin:
        call = cases[int(line)]
        start = time.perf_counter()
        call()
        print(time.perf_counter() - start, flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("first", help="PYTHONPATH of the first build's module (e.g. build/python)")
    parser.add_argument("second", help="PYTHONPATH of the second build's module")
    parser.add_argument("--reps", type=int, default=15)
    args = parser.parse_args()
    children = [subprocess.Popen([sys.executable, __file__, "--child"], env=dict(os.environ, PYTHONPATH=path),
                                 stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
                for path in (args.first, args.second)]
    isas = [c.stdout.readline().strip() for c in children]

    def timed(build, case):
        children[build].stdin.write(f"{case}\n")
        children[build].stdin.flush()
        return float(children[build].stdout.readline())

    print(f"first: {args.first} (path {isas[0]}); second: {args.second} (path {isas[1]}); {args.reps} paired repetitions\n")
    print("| workload | first ns/vector | second ns/vector | second / first (paired) |")
    print("| --- | --- | --- | --- |")
    for case, (what, count) in enumerate(names()):
        timed(0, case), timed(1, case)
        times, ratios = ([], []), []
        for rep in range(args.reps):
            pair = [0.0, 0.0]
            for b in ((0, 1) if rep % 2 == 0 else (1, 0)):
                pair[b] = timed(b, case)
                times[b].append(pair[b])
            ratios.append(pair[1] / pair[0])
        a, b = (float(np.median(t)) / count * 1e9 for t in times)
        print(f"| {what} | {a:.2f} | {b:.2f} | {float(np.median(ratios)):.3f} |")
    for c in children:
        c.stdin.close()
        c.wait()


if __name__ == "__main__":
    if sys.argv[1:] == ["--child"]:
        child()
    else:
        main()
