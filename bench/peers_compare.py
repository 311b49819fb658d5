#!/usr/bin/env python3
"""The default build against the x86-64-v3 build, from two reports of the peer harness.

Usage: peers_compare.py DEFAULT_REPORT X86_64_V3_REPORT

DEFAULT_REPORT is the harness built without -march with zhf's row through zhf::dispatch
(bench/peers.sh writes it); X86_64_V3_REPORT the harness built -march=x86-64-v3 with the
header-only rows. Prints one markdown row per order: the dispatch row's median, the fastest
header-only float row's, their ratio (the goal: at most 1.10) and DirectXMath over zhf in each
build (the goal: above 1 in the default build).
"""
import re
import sys

WITHIN = 1.10  # the default build within 10 % of the x86-64-v3 build


def read(path):
    """{order: [(name, precision, median ns)]} from one report."""
    orders, order = {}, None
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = re.match(r"== N = (\d+) ", line)
            if m:
                order = int(m.group(1))
                orders[order] = []
                continue
            fields = line.split()
            if order is None or len(fields) < 11 or fields[-10] not in ("float", "double"):
                continue
            try:
                median = float(fields[-9])
            except ValueError:
                continue
            orders[order].append((" ".join(fields[:-10]), fields[-10], median))
    return orders


def zhf_float(rows, dispatch):
    """The fastest zhf float row: the dispatch row, or the header-only rows built with the flags."""
    rows = [r for r in rows if r[0].startswith("zhf") and r[1] == "float" and "no -march" not in r[0]
            and ("dispatch" in r[0]) == dispatch]
    return min(rows, key=lambda r: r[2]) if rows else None


def directxmath(rows):
    rows = [r for r in rows if r[0].startswith("DirectXMath")]
    return rows[0][2] if rows else None


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[2])
    default, v3 = read(sys.argv[1]), read(sys.argv[2])
    print("| N | default build: dispatch ns | x86-64-v3: fastest zhf ns (row) | default / x86-64-v3 "
          "| DirectXMath / zhf, default build | DirectXMath / zhf, x86-64-v3 build |")
    print("| --- | --- | --- | --- | --- | --- |")
    missed = []
    for order in sorted(default):
        d, v = zhf_float(default[order], True), zhf_float(v3.get(order, []), False)
        if d is None or v is None:
            continue
        ratio = d[2] / v[2]
        dxm_d, dxm_v = directxmath(default[order]), directxmath(v3.get(order, []))
        cell = lambda dxm, zhf: f"{dxm / zhf:.2f}x" if dxm else "-"
        print(f"| {order} | {d[2]:.1f} | {v[2]:.1f} ({v[0]}) | {ratio:.2f} | {cell(dxm_d, d[2])} | {cell(dxm_v, v[2])} |")
        if ratio > WITHIN:
            missed.append(f"order {order}: default / x86-64-v3 {ratio:.2f} > {WITHIN}")
        if dxm_d and dxm_d <= d[2]:
            missed.append(f"order {order}: DirectXMath ahead in the default build")
    for m in missed:
        print("missed:", m)


if __name__ == "__main__":
    main()
