#!/usr/bin/env python3
"""The tables of docs/performance.md, from the raw files benchmarks/performance.sh writes.

Usage: performance_tables.py RESULTS_DIR              print every table (Markdown)
       performance_tables.py --check DOCUMENT...      exit 1 if a table block of a DOCUMENT is stale
       performance_tables.py --update DOCUMENT...     rewrite the DOCUMENTs' table blocks

Reads peers_*.txt (the peer harness), fma_bound.txt, bulk_*.txt, splat_builds.txt,
python_builds*.txt and bench.json of one run of benchmarks/performance.sh, and makes each table with
the file it comes from and that file's provenance line. In a document a block

    <!-- table NAME from RESULTS_DIR: benchmarks/performance_tables.py writes it, do not edit -->
    ...
    <!-- end table -->

holds table NAME (peers_x86_64_v3, peers_default_build, goals, builds, fma_bound, bulk, splat_builds, python,
bench; tight_frame, prt_reference and prt_errors for docs/frames.md, products for docs/products.md,
numerical_limits and chain for docs/verification.md, web_splats for docs/web.md) made from RESULTS_DIR, relative to the repository. Nothing is measured here.
"""
import contextlib
import io
import json
import os
import re
import sys

ROW = re.compile(r"^(.*?)\s+(float|double)\s+([\d.]+)\s+([\d.]+)\s+([\d.e+-]+)\s")
PEERS = [
    ("DirectXMath", "DirectXMath XMSHRotate", "float"),
    ("Filament (order 3)", "Filament", "float"),
    ("sh-lib", "sh-lib RRotateSH (as shipped)", "float"),
    ("Ivanic-Ruedenberg (the harness's, float)", "plain Ivanic-Ruedenberg (this harness)", "float"),
    ("google (float)", "google Rotation::Create+Apply<float>", "float"),
    ("HEALPix (double, with conversion)", "HEALPix rotate_alm<double> (+conversion)", "double"),
]


def header(path):
    """The two '#' lines benchmarks/record.sh writes, as one line of provenance."""
    with open(path) as f:
        lines = [next(f).rstrip("\n"), next(f).rstrip("\n")]
    return " ".join(l.lstrip("# ").strip() for l in lines)


def read_peers(path):
    """{order: [(method, precision, median ns, max err)]}."""
    orders, order = {}, None
    for line in open(path):
        m = re.match(r"== N = (\d+) ", line)
        if m:
            order = int(m.group(1))
            orders[order] = []
            continue
        m = ROW.match(line)
        if order is not None and m and not line.startswith("method"):
            orders[order].append((m.group(1).strip(), m.group(2), float(m.group(3)), float(m.group(5))))
    return orders


def read_run(results, build):
    """One build's peer runs, orders 2..64 and 128 together."""
    orders = read_peers(os.path.join(results, f"peers_{build}.txt"))
    orders.update(read_peers(os.path.join(results, f"peers_{build}_order128.txt")))
    return orders


def zhf_fastest(rows):
    """The fastest zhf float row built with the run's flags (not the harness's baseline rows)."""
    native = [r for r in rows if r[0].startswith("zhf") and r[1] == "float" and "no -march" not in r[0]]
    return min(native, key=lambda r: r[2]) if native else None


def peer_time(rows, name, precision):
    """The median of the peer row whose method starts with name, or None."""
    match = [r[2] for r in rows if r[0].startswith(name) and r[1] == precision]
    return match[0] if match else None


def path_name(method):
    """A zhf row's path, short: the harness's method names without the row's type and call."""
    isa = re.search(r"\[(\w+)\]$", method)
    if "dispatch" in method:
        return f"`{isa.group(1)}` path" if isa else "dispatch"
    for text, name in (("bands 0 and 1", "bands 0 and 1 in one register"), ("rotate_lanes", "lanes"), ("band rows", "band rows"),
                       ("from_table", "`from_table`: zxzxz"), ("zxzxz", "zxzxz"), ("rotate_orderN", "scalar kernel")):
        if text in method:
            return name
    return method


def fmt(ns):
    return f"{ns:.1f}" if ns < 1e4 else f"{ns:.0f}"


def peers_table(results, build, zhf_label):
    """One row per order: zhf's fastest path of the build against every peer, and the ratios."""
    path, big = (os.path.join(results, f"peers_{build}{tail}.txt") for tail in ("", "_order128"))
    print(f"Source: `{path}` (order 128: `{big}`, K = 4, 3 repetitions).  ")
    print(f"Run: {header(path)}\n")
    print(f"| N | {zhf_label}: median ns (path) / max err | " + " | ".join(p[0] for p in PEERS) + " | DirectXMath / zhf | HEALPix / zhf |")
    print("| --- " * (len(PEERS) + 4) + "|")
    for order, rows in sorted(read_run(results, build).items()):
        best = zhf_fastest(rows)
        if not best:
            continue
        found = {label: peer_time(rows, name, precision) for label, name, precision in PEERS}
        cells = [f"{fmt(best[2])} ({path_name(best[0])}) / {best[3]:.1e}"] + [fmt(t) if t else "-" for t in found.values()]
        ratio = lambda label: f"{found[label] / best[2]:.3g}x" if found[label] else "-"
        print(f"| {order} | " + " | ".join(cells) + f" | {ratio('DirectXMath')} | {ratio('HEALPix (double, with conversion)')} |")
    print()


# The goals of the performance work: (order, against what, the bound). "DirectXMath": its time over
# zhf's at the order, at least the bound; "DirectXMath N = 6": zhf's time over DirectXMath's at
# N = 6, at most the bound; "HEALPix": its time over zhf's, at least the bound.
GOALS = [(2, "DirectXMath", 2.5), (3, "DirectXMath", 1.8), (4, "DirectXMath", 1.6), (5, "DirectXMath", 1.4),
         (6, "DirectXMath", 1.4), (7, "DirectXMath N = 6", 1.6), (8, "DirectXMath N = 6", 2.5),
         (16, "DirectXMath N = 6", 10), (32, "DirectXMath N = 6", 65), (32, "HEALPix", 10), (64, "HEALPix", 10),
         (128, "HEALPix", 10)]


def goals_table(results):
    """Each goal against both builds' peer runs."""
    builds = []
    for build in ("x86_64_v3", "default_build"):
        times = {}
        for order, rows in read_run(results, build).items():
            best = zhf_fastest(rows)
            times[order] = (best[2] if best else None, peer_time(rows, "DirectXMath", "float"),
                            peer_time(rows, "HEALPix rotate_alm<double>", "double"))
        builds.append(times)
    print(f"Source: the two peer runs above (`{results}/peers_*.txt`).\n")
    print("| N | goal | `-march=x86-64-v3` | met | no `-march` (`zhf::dispatch`) | met |\n| --- | --- | --- | --- | --- | --- |")
    for order, against, bound in GOALS:
        what = {"DirectXMath": f">= {bound}x DirectXMath", "DirectXMath N = 6": f"<= {bound}x DirectXMath's N = 6 time",
                "HEALPix": f">= {bound}x HEALPix"}[against]
        cells = []
        for times in builds:
            z, d, h = times.get(order, (None, None, None))
            d6 = times.get(6, (None, None, None))[1]
            over = {"DirectXMath": (d, z), "DirectXMath N = 6": (z, d6), "HEALPix": (h, z)}[against]
            if None in over:
                cells += ["-", "-"]
                continue
            value = over[0] / over[1]
            met = value <= bound if against == "DirectXMath N = 6" else value >= bound
            cells += [f"{value:.2f}x", "yes" if met else "**no**"]
        print(f"| {order} | {what} | " + " | ".join(cells) + " |")
    print()


# The default build's zhf::dispatch within this factor of the x86-64-v3 build's fastest path.
WITHIN = 1.10


def builds_table(results):
    """As users get it against -march=x86-64-v3: zhf::dispatch over the header-only fastest path."""
    default, v3 = read_run(results, "default_build"), read_run(results, "x86_64_v3")
    print(f"Source: the two peer runs above (`{results}/peers_*.txt`).\n")
    print(f"| N | no `-march`: `zhf::dispatch` ns | `-march=x86-64-v3`: fastest ns (path) | no `-march` / x86-64-v3 (goal <= {WITHIN:.2f}) |")
    print("| --- | --- | --- | --- |")
    for order in sorted(default):
        d, v = zhf_fastest(default[order]), zhf_fastest(v3.get(order, []))
        if d and v:
            ratio = d[2] / v[2]
            print(f"| {order} | {fmt(d[2])} | {fmt(v[2])} ({path_name(v[0])}) | {ratio:.2f}{'' if ratio <= WITHIN else ' **missed**'} |")
    print()


def fma_table(results):
    """Every path's measured time per order and its distance from the bound, side by side."""
    path = os.path.join(results, "fma_bound.txt")
    print(f"Source: `{path}`.  \nRun: {header(path)}\n")
    paths, isa, clock = {}, None, ""
    for line in list(open(path))[2:]:
        m = re.match(r"^(\w+) \((\d+) float lanes(, FMA|, no FMA)", line)
        if m:
            isa = f"`{m.group(1)}` ({m.group(2)} floats{m.group(3)})"
            paths[isa] = {}
        elif line.startswith("clock"):
            clock = line.strip()
        m = re.match(r"^\| (\d+) \| (\S+) \| ([\d.]+) \| ([\d.]+) \| (\S+) \| (\S+) \|", line)
        if m and isa:
            paths[isa][int(m.group(1))] = m.groups()[1:]
    print(f"{clock}. Per path: the kernels it runs, measured ns, and measured / bound (the bound's ns in brackets).\n")
    print("| N | " + " | ".join(paths) + " |\n" + "| --- " * (len(paths) + 1) + "|")
    for order in sorted({o for rows in paths.values() for o in rows}):
        cells = []
        for rows in paths.values():
            kernel, _, bound_ns, measured, ratio = rows.get(order, ("-",) * 5)
            cells.append("-" if measured == "-" else f"{kernel} {measured} ns, {ratio}x ({bound_ns})")
        print(f"| {order} | " + " | ".join(cells) + " |")
    print()


BULK = re.compile(r"N=(\d+) threads=(\d+) items=(\d+) .*?copy ([\d.]+) GB/s; splats ([\d.]+) ns/item [\d.]+ GB/s (\d+)% of copy, "
                  r"in place [\d.]+ ns/item (\d+)%; planar ([\d.]+) ns/item [\d.]+ GB/s (\d+)% of copy, in place [\d.]+ ns/item (\d+)%")
SOA = re.compile(r"N=(\d+) soa, (\d+) rotations, planes (\d+) apart, one thread: rotate_soa ([\d.]+) ns per rotation; "
                 r"generated rotate_batch ([\d.]+ ns|-); scalar rotate per rotation ([\d.]+) ns \(([\d.]+)x rotate_soa\)")


def bulk_table(results):
    """One rotation for many items (both builds, both counts), then SoA (both builds)."""
    files = {name: os.path.join(results, name + ".txt") for name in ("bulk_x86_64_v3", "bulk_default_build", "bulk_x86_64_v3_odd_counts")}
    for name, path in files.items():
        print(f"Source: `{path}`.  \nRun: {header(path)}  ")
    print("\nOne rotation for many items: copy rate, then ns per item and the rate as a share of the copy's, out of place; in place")
    print("\n| build, items | N | threads | copy GB/s | 3DGS layout | planar |\n| --- | --- | --- | --- | --- | --- |")
    for name, label in (("bulk_x86_64_v3", "x86-64-v3"), ("bulk_x86_64_v3_odd_counts", "x86-64-v3, no power of two"),
                        ("bulk_default_build", "no -march")):
        for line in open(files[name]):
            m = BULK.match(line)
            if m:
                n, threads, items, copy, splat_ns, splat, splat_in, planar_ns, planar, planar_in = m.groups()
                print(f"| {label}, {items} | {n} | {threads} | {copy} | {splat_ns} ns, {splat} %; {splat_in} % | "
                      f"{planar_ns} ns, {planar} %; {planar_in} % |")
    print("\nMany rotations, SoA, one thread: ns per rotation, `rotate_soa` / generated `rotate_batch_orderN` loop / scalar kernel "
          "per rotation, and scalar / `rotate_soa`\n")
    layouts = [("4096", "4096"), ("4096", "4128"), ("4000", "4000")]
    print("| build | N | " + " | ".join(f"{c} rotations, planes {p} apart" for c, p in layouts) + " |")
    print("| --- " * (len(layouts) + 2) + "|")
    for name, label in (("bulk_x86_64_v3", "x86-64-v3"),):  # without -march: the file
        rows = {}
        for line in open(files[name]):
            m = SOA.match(line)
            if m:
                n, count, stride, soa, loop, scalar, ratio = m.groups()
                rows.setdefault(int(n), {})[(count, stride)] = f"{soa} / {loop.replace(' ns', '')} / {scalar}, **{ratio}x**"
        for n in sorted(rows):
            print(f"| {label} | {n} | " + " | ".join(rows[n].get(l, "-") for l in layouts) + " |")
    print()


def splat_table(results):
    path = os.path.join(results, "splat_builds.txt")
    print(f"Source: `{path}`.  \nRun: {header(path)}\n")
    print("| pairing | A wall s (median) | B wall s (median) | A/B wall (median) |")
    print("| --- | --- | --- | --- |")
    title, a = None, None
    for line in open(path):
        if line.startswith("## "):
            title = line[3:].strip()
        m = re.match(r"^([AB]) wall s\s+[\d.]+\s+([\d.]+)", line)
        if m and m.group(1) == "A":
            a = m.group(2)
        elif m:
            b = m.group(2)
        m = re.match(r"^A/B wall\s+[\d.]+\s+([\d.]+)", line)
        if m:
            print(f"| {title} | {a} | {b} | {m.group(1)} |")
    print()


def python_table(results):
    """The two runs (each build first in one) side by side."""
    runs = []
    for name in ("python_builds", "python_builds_swapped"):
        path = os.path.join(results, name + ".txt")
        print(f"Source: `{path}`.  \nRun: {header(path)}  ")
        rows = {}
        for line in open(path):
            m = re.match(r"^\| (order [^|]+) \| ([\d.]+) \| ([\d.]+) \| ([\d.]+) \|", line)
            if m:
                rows[m.group(1).strip()] = m.groups()[1:]
        runs.append(rows)
    print("\nns per vector, medians of the pairs; the ratio default / x86-64-v3, in the run with the default build first and "
          "in the one with it second\n")
    print("| workload | no `-march` | `-march=x86-64-v3` | ratio, default first | ratio, x86-64-v3 first |\n| --- | --- | --- | --- | --- |")
    for what, (a, b, ratio) in runs[0].items():
        swapped = runs[1].get(what)
        other = f"{float(swapped[2]):.3f}" if swapped else "-"
        print(f"| {what} | {a} | {b} | {float(ratio) and 1 / float(ratio):.3f} | {other} |")
    print()


def bench_table(results):
    """zhf bench: per scenario and order, each method's fastest row (the plots' points)."""
    path = os.path.join(results, "bench.json")
    report = json.load(open(path))
    print(f"Source: `{path}` ({report.get('cpu', '')}; {report.get('flags', '')}; {report.get('date', '')}).\n")
    # The other scenarios are in the file and the scenario plot (bulk paths: their own table).
    panels = [("single", None, "One vector, a new rotation per call")]
    for scenario, variant, title in panels:
        best = {}
        for r in report["rows"]:
            if r["scenario"] != scenario or (variant and r["variant"] != variant) or r["variant"] == "conversion only":
                continue
            method = r["method"] + (" (double)" if r["precision"] == "double" else "")
            key = (method, r["order"])
            if key not in best or r["ns_median"] < best[key]["ns_median"]:
                best[key] = r
        methods = sorted({m for m, _ in best})
        orders = sorted({o for _, o in best})
        print(f"{title}: median ns / max error, each method's fastest path\n")
        print("| N | " + " | ".join(methods) + " |")
        print("| --- " * (len(methods) + 1) + "|")
        for o in orders:
            cells = []
            for m in methods:
                r = best.get((m, o))
                cells.append(f"{r['ns_median']:.3g} / {r['max_error']:.1e}" if r and r.get("max_error") is not None else
                              (f"{r['ns_median']:.3g}" if r else "-"))
            print(f"| {o} | " + " | ".join(cells) + " |")
        print()


def bench_rows(results):
    path = os.path.join(results, "bench.json")
    report = json.load(open(path))
    print(f"Source: `{path}` ({report.get('cpu', '')}; {report.get('flags', '')}; {report.get('date', '')}).\n")
    return report["rows"]


def tight_frame_table(results):
    """The tight-frame rotation against the run-time path and the recurrence (docs/frames.md)."""
    rows = bench_rows(results)
    pick = lambda method, order: min((r for r in rows if r["method"] == method and r["scenario"] == "single" and r["order"] == order
                                      and r["precision"] == ("double" if method == "ivanic_ruedenberg" else "float")),
                                     key=lambda r: r["ns_median"], default=None)
    print("| N | lobes (design) | tight frame ns | run-time path (`from_table`) ns | Ivanic-Ruedenberg (double) ns | tight frame max err "
          "| worst unit input |\n| --- | --- | --- | --- | --- | --- | --- |")
    for order in sorted({r["order"] for r in rows if r["method"] == "tight_frame"}):
        t, z, ir = pick("tight_frame", order), pick("zhf_runtime", order), pick("ivanic_ruedenberg", order)
        runtime = f"{z['ns_median']:.0f}" if z else "-"
        print(f"| {order} | {t['variant']} | {t['ns_median']:.0f} | {runtime} | {ir['ns_median']:.0f} | "
              f"{t['max_error']:.1e} | {t['worst_unit_error']:.1e} |")
    print()


def products_table(results):
    """The product, square and shading kernels against the sparse Gaunt loop (docs/products.md)."""
    rows = bench_rows(results)
    columns = [("product", "zhf", "float", "product"), ("product (double)", "zhf", "double", "product"),
               ("gaunt_sparse", "gaunt_sparse", "float", "product"), ("square", "zhf", "float", "square"),
               ("shade", "zhf_shade", "float", "shade"), ("rotate, then dot", "zhf_rotate_then_dot", "float", "shade"),
               ("shade_lobes", "zhf_shade_lobes", "float", "shade")]
    print("ns per call, median:\n")
    print("| N | " + " | ".join(c[0] for c in columns) + " |\n" + "| --- " * (len(columns) + 1) + "|")
    for order in sorted({r["order"] for r in rows if r["scenario"] == "product"}):
        cells = []
        for _, method, precision, scenario in columns:
            match = [r for r in rows if r["method"] == method and r["precision"] == precision and r["scenario"] == scenario and r["order"] == order]
            cells.append(f"{match[0]['ns_median']:.1f}" if match else "-")
        print(f"| {order} | " + " | ".join(cells) + " |")
    print()


def prt_reference_table(results):
    """The exact PRT reference's convergence (benchmarks/prt.sh's reference.txt), as it printed it."""
    path = os.path.join(results, "reference.txt")
    print(f"Source: `{path}`.  \nRun: {header(path)}\n")
    for line in open(path):
        if line.startswith("|"):
            print(line.rstrip("\n"))
    print()


def prt_errors_table(results):
    """SH bands / SH's K largest / needlets, RMS error per scene and transfer (benchmarks/prt.sh's runs)."""
    kept = (16, 64, 256, 1024)
    print(f"Source: `{results}/<scene>_<transfer>.txt`.  \nRun: {header(os.path.join(results, 'sphere_diffuse.txt'))}\n")
    print("| scene, transfer | " + " | ".join(f"K = {k}" for k in kept) + " | all (SH 1024, needlets 4667) |")
    print("| --- " * (len(kept) + 2) + "|")
    for scene in ("sphere", "corner", "spheres"):
        for transfer in ("diffuse", "glossy"):
            rows = {}
            for line in list(open(os.path.join(results, f"{scene}_{transfer}.txt")))[2:]:
                fields = line.split()
                if len(fields) == 12 and fields[0].isdigit():
                    rows[int(fields[0])] = (float(fields[1]), float(fields[3]), float(fields[5]))
            cells = [" / ".join(f"{v:.1e}" for v in rows[k]) for k in kept]
            print(f"| {scene}, {transfer} | " + " | ".join(cells) + f" | {rows[max(rows)][0]:.1e} |")
    print()


def markdown_of(name):
    """A raw file's Markdown tables and its closing lines, as the program printed them."""
    def table(results):
        path = os.path.join(results, name)
        print(f"Source: `{path}`.  \nRun: {header(path)}\n")
        table = False
        for line in list(open(path))[2:]:
            if line.strip():
                row = line.startswith("|")
                # A table stands after a blank line, as does a line of text.
                print(("\n" if not row or not table else "") + line.rstrip("\n"))
                table = row
        print()
    return table


SECTIONS = {
    "peers_x86_64_v3": lambda r: peers_table(r, "x86_64_v3", "zhf, fastest path"),
    "peers_default_build": lambda r: peers_table(r, "default_build", "zhf::dispatch"),
    "goals": goals_table,
    "builds": builds_table,
    "fma_bound": fma_table,
    "bulk": bulk_table,
    "splat_builds": splat_table,
    "python": python_table,
    "bench": bench_table,
    "tight_frame": tight_frame_table,
    "products": products_table,
    "prt_reference": prt_reference_table,
    "prt_errors": prt_errors_table,
    "numerical_limits": markdown_of("numerical_limits.txt"),
    "chain": markdown_of("chain.txt"),
    "web_splats": markdown_of("web_splats.txt"),
}
BLOCK = re.compile(r"(<!-- table (\w+) from ([\w/.-]+): benchmarks/performance_tables.py writes it, do not edit -->\n)(.*?)(<!-- end table -->)",
                   re.S)


def section(name, results):
    """One table as text, its paths relative to the repository."""
    out = io.StringIO()
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    cwd = os.getcwd()
    os.chdir(root)
    try:
        with contextlib.redirect_stdout(out):
            SECTIONS[name](results)
    finally:
        os.chdir(cwd)
    return out.getvalue()


def main():
    if len(sys.argv) >= 3 and sys.argv[1] in ("--check", "--update"):
        stale = []
        for document in sys.argv[2:]:
            text = open(document).read()

            def fill(m):
                if m.group(2) not in SECTIONS:
                    sys.exit(f"{document}: no table named {m.group(2)}")
                made = section(m.group(2), m.group(3))
                if made != m.group(4):
                    stale.append(f"{document}: {m.group(2)}")
                return m.group(1) + made + m.group(5)

            updated = BLOCK.sub(fill, text)
            if sys.argv[1] == "--update" and updated != text:
                with open(document + ".tmp", "w") as f:
                    f.write(updated)
                os.replace(document + ".tmp", document)
            print(f"{document}: {len(BLOCK.findall(text))} table blocks")
        if stale and sys.argv[1] == "--check":
            sys.exit(f"stale tables: {'; '.join(stale)} (python3 benchmarks/performance_tables.py --update DOCUMENT)")
        return
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    for name in SECTIONS:
        print(f"## {name}\n")
        print(section(name, sys.argv[1]))


if __name__ == "__main__":
    main()
