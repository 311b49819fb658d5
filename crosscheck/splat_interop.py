"""zhf splat and @playcanvas/splat-transform on each other's files: for every format and SH degree
0..4, a scene written by one tool and read by the other, both directions.

    python3 crosscheck/splat_interop.py ZHF SPLAT_TRANSFORM [--splats N] > table.md

Each cell reads the file with both tools where both read the format, and gives the largest
difference between the two decodes (positions, log-scales, alpha, colour, SH, and the
orientation's quaternion up to sign), naming the field; where only one tool reads the format, the
largest difference from the scene written (the format's own steps included, marked "vs scene").
A tool that refuses says so, with the first line of its message. The scene: random splats inside
every format's range (seeded), so that no value is clamped.
"""

import argparse
import math
import random
import re
import struct
import subprocess
import sys
import tempfile
from pathlib import Path

FORMATS = [".ply", ".compressed.ply", ".splat", ".spz", ".glb", ".sog"]
# What splat-transform 3.7 reads and writes (its --help); it writes SOG on the CPU with -g cpu.
ST_READS = {".ply", ".compressed.ply", ".splat", ".spz", ".sog"}
ST_WRITES = {".ply", ".compressed.ply", ".spz", ".glb", ".sog"}


def rest_count(degree):
    return 3 * ((degree + 1) ** 2 - 1)


def write_scene(path, degree, splats, seed, band_scale=lambda band: 1.0):
    """Random splats inside every format's range; SH band l's coefficients times band_scale(l)."""
    rng = random.Random(seed)
    per_channel = (degree + 1) ** 2 - 1
    names = ["x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"]
    names += [f"f_rest_{i}" for i in range(rest_count(degree))]
    names += ["opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"]
    header = f"ply\nformat binary_little_endian 1.0\nelement vertex {splats}\n"
    header += "".join(f"property float {n}\n" for n in names) + "end_header\n"
    out = bytearray(header.encode())
    for _ in range(splats):
        row = [rng.uniform(-50, 50) for _ in range(3)] + [0.0, 0.0, 0.0]
        row += [rng.uniform(-1.5, 1.5) for _ in range(3)]
        row += [rng.uniform(-0.9, 0.9) * band_scale(math.isqrt(j % per_channel + 1)) for j in range(rest_count(degree))]
        row += [rng.uniform(-4, 4)] + [rng.uniform(-8, 3) for _ in range(3)]
        q = [rng.uniform(-1, 1) for _ in range(4)]
        norm = math.sqrt(sum(x * x for x in q))
        row += [x / norm for x in q]
        out += struct.pack(f"<{len(row)}f", *row)
    Path(path).write_bytes(out)


def read_ply(path):
    """A binary little-endian PLY of float properties, as {name: [values]}."""
    data = Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    lines = data[:end].decode().splitlines()
    count = next(int(l.split()[2]) for l in lines if l.startswith("element vertex"))
    names = [l.split()[2] for l in lines if l.startswith("property")]
    assert all(l.split()[1] == "float" for l in lines if l.startswith("property")), path
    values = struct.unpack_from(f"<{count * len(names)}f", data, end)
    return {n: values[i::len(names)] for i, n in enumerate(names)}


def degree_of(decoded):
    return math.isqrt(sum(1 for n in decoded if n.startswith("f_rest_")) // 3 + 1) - 1


def largest_difference(a, b, degree):
    """(difference, field) over the fields both decodes hold."""
    worst = (0.0, "none")
    per_channel = (degree + 1) ** 2 - 1
    count = len(a["x"])

    def note(value, field):
        nonlocal worst
        if value > worst[0]:
            worst = (value, field)

    for k in range(count):
        for n in ("x", "y", "z", "scale_0", "scale_1", "scale_2", "f_dc_0", "f_dc_1", "f_dc_2"):
            note(abs(a[n][k] - b[n][k]), n.rstrip("_012") if n[0] != "f" else "f_dc")
        alpha = [1 / (1 + math.exp(-max(-80.0, min(80.0, s[k])))) for s in (a["opacity"], b["opacity"])]
        note(abs(alpha[0] - alpha[1]), "alpha")
        qa = [a[f"rot_{i}"][k] for i in range(4)]
        qb = [b[f"rot_{i}"][k] for i in range(4)]
        na, nb = math.sqrt(sum(x * x for x in qa)), math.sqrt(sum(x * x for x in qb))
        same = max(abs(x / na - y / nb) for x, y in zip(qa, qb))
        opposite = max(abs(x / na + y / nb) for x, y in zip(qa, qb))
        note(min(same, opposite), "rotation")
        for j in range(3 * per_channel):
            name = f"f_rest_{j}"
            if name in a and name in b:
                note(abs(a[name][k] - b[name][k]), f"SH band {int(math.isqrt(j % per_channel + 1))}")
    return worst


def run(args):
    """Exit code and output lines, zhf's "zhf: <temporary path>: " prefix left out."""
    result = subprocess.run(args, capture_output=True, text=True)
    lines = (result.stderr.strip() or result.stdout.strip()).splitlines()
    return result.returncode, [re.sub(r"^zhf: \S+: ", "", l).replace("✗ ", "") for l in lines]


def zhf_read(zhf, path, out):
    code, lines = run([zhf, "splat", "--in", path, "--out", out, "--quiet"])
    return None if code == 0 else (lines[0] if lines else f"exit {code}")


def st_read(st, path, out):
    code, lines = run([st, "-w", "-q", path, out])
    if code == 0:
        return None
    errors = [l for l in lines if "Error" in l] or lines
    return errors[0].strip() if errors else f"exit {code}"


def cell(writer, path, scene, degree, zhf, st, tmp):
    """Both tools read `path` (written by `writer`) where they can; the cell's text."""
    fmt = next(f for f in sorted(FORMATS, key=len, reverse=True) if path.endswith(f))
    reader = "splat-transform" if writer == "zhf" else "zhf"
    reads = fmt in ST_READS if reader == "splat-transform" else True
    if not reads:
        return f"{reader} does not read {fmt}"
    z_out, s_out = str(Path(tmp) / "z.ply"), str(Path(tmp) / "s.ply")
    z_error = zhf_read(zhf, path, z_out)
    s_error = st_read(st, path, s_out) if fmt in ST_READS else None
    if reader == "zhf" and z_error:
        return f"zhf refuses: {z_error[:120]}"
    if reader == "splat-transform" and s_error:
        return f"splat-transform refuses: {s_error[:120]}"
    if z_error or s_error:
        other = "zhf" if z_error else "splat-transform"
        return f"{other} cannot read it back: {(z_error or s_error)[:120]}"
    if fmt not in ST_READS:
        difference, field = largest_difference(read_ply(z_out), read_ply(scene), degree)
        return f"reads; {difference:.2g} ({field}) vs scene"
    a, b = read_ply(z_out), read_ply(s_out)
    kept = min(degree, degree_of(a), degree_of(b))
    difference, field = largest_difference(a, b, kept)
    suffix = "" if kept == degree else f", degree {kept} kept"
    return f"agree to {difference:.2g} ({field}){suffix}"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("zhf")
    parser.add_argument("splat_transform")
    parser.add_argument("--splats", type=int, default=2000)
    a = parser.parse_args()
    shown = subprocess.run([a.splat_transform, "--version"], capture_output=True, text=True)
    version = (shown.stdout.strip() or shown.stderr.strip()).splitlines()[0]
    print(f"zhf splat and {version}, {a.splats} random splats per scene (seeded), each tool's defaults")
    print()
    print("| format | SH degree | zhf writes, splat-transform reads | splat-transform writes, zhf reads |")
    print("| --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as tmp:
        for fmt in FORMATS:
            for degree in range(5):
                scene = str(Path(tmp) / f"scene{degree}.ply")
                write_scene(scene, degree, a.splats, 1000 + degree)
                by_zhf, by_st = str(Path(tmp) / ("zhf" + fmt)), str(Path(tmp) / ("st" + fmt))
                # zhf writes a SOG from a SOG only: it turns splat-transform's (by the identity).
                source = by_st if fmt == ".sog" else scene
                if fmt == ".sog":
                    code, lines = run([a.splat_transform, "-w", "-q", "-g", "cpu", scene, by_st])
                    if code != 0:
                        source = None
                if source is None:
                    left = "zhf writes a .sog from a .sog; splat-transform wrote none"
                else:
                    code, lines = run([a.zhf, "splat", "--in", source, "--out", by_zhf, "--quiet"])
                    left = cell("zhf", by_zhf, scene, degree, a.zhf, a.splat_transform, tmp) if code == 0 else f"zhf refuses to write: {lines[0][:120]}"
                if fmt not in ST_WRITES:
                    right = f"splat-transform does not write {fmt}"
                else:
                    extra = ["-g", "cpu"] if fmt == ".sog" else []
                    code, lines = run([a.splat_transform, "-w", "-q", *extra, scene, by_st])
                    if code != 0:
                        errors = [l for l in lines if "Error" in l] or lines
                        right = f"splat-transform refuses to write: {errors[0].strip()[:120] if errors else code}"
                    else:
                        right = cell("splat-transform", by_st, scene, degree, a.zhf, a.splat_transform, tmp)
                print(f"| {fmt} | {degree} | {left} | {right} |")
                sys.stdout.flush()


if __name__ == "__main__":
    main()
