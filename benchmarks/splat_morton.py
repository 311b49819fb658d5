"""The position error Morton order saves in a compressed .ply: zhf splat writes one scene in the
input's order (--keep-order) and in Morton order (the default), and each splat's decoded position
is compared with the scene's (splats matched by their SH bytes, which do not depend on the chunk).

    python3 benchmarks/splat_morton.py ZHF [--splats N] > table.md

The scene: random splats (crosscheck/splat_interop.py's, seeded) with positions uniform in a 100-unit
cube, in random order, as a scene whose splats were never sorted.
"""

import argparse
import math
import struct
import subprocess
import tempfile
from pathlib import Path

from splat_interop import read_ply, write_scene


def read_compressed(path):
    """Positions and SH bytes of each splat of a compressed .ply, decoded from its layout."""
    data = Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    lines = data[:end].decode().splitlines()
    counts = {l.split()[1]: int(l.split()[2]) for l in lines if l.startswith("element")}
    chunk_floats = sum(1 for l in lines if l.startswith("property float"))
    rest = sum(1 for l in lines if l.startswith("property uchar"))
    chunks = struct.unpack_from(f"<{counts['chunk'] * chunk_floats}f", data, end)
    packed_at = end + 4 * counts["chunk"] * chunk_floats
    words = struct.unpack_from(f"<{4 * counts['vertex']}I", data, packed_at)
    sh_at = packed_at + 16 * counts["vertex"]
    out = []
    for k in range(counts["vertex"]):
        b = chunks[(k // 256) * chunk_floats:(k // 256 + 1) * chunk_floats]
        word = words[4 * k]
        position = []
        for i, (shift, bits) in enumerate(((21, 11), (11, 10), (0, 11))):
            t = ((word >> shift) & ((1 << bits) - 1)) / ((1 << bits) - 1)
            position.append(b[i] * (1 - t) + b[3 + i] * t)
        out.append((position, data[sh_at + rest * k:sh_at + rest * (k + 1)]))
    return out


def errors(decoded, scene, index_of):
    worst, squares = 0.0, 0.0
    for position, key in decoded:
        k = index_of[key]
        for i, axis in enumerate("xyz"):
            e = abs(position[i] - scene[axis][k])
            worst = max(worst, e)
            squares += e * e
    return worst, math.sqrt(squares / (3 * len(decoded)))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("zhf")
    parser.add_argument("--splats", type=int, default=200000)
    a = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        scene_path, kept, sorted_path = (str(Path(tmp) / n) for n in ("scene.ply", "kept.compressed.ply", "sorted.compressed.ply"))
        write_scene(scene_path, 3, a.splats, 11)
        subprocess.run([a.zhf, "splat", "--in", scene_path, "--out", kept, "--quiet", "--keep-order"], check=True)
        subprocess.run([a.zhf, "splat", "--in", scene_path, "--out", sorted_path, "--quiet"], check=True)
        scene = read_ply(scene_path)
        in_order = read_compressed(kept)
        index_of = {key: k for k, (_, key) in enumerate(in_order)}
        assert len(index_of) == a.splats, "SH bytes name each splat"
        print(f"zhf splat into a compressed .ply, {a.splats} degree-3 splats, positions uniform in a 100-unit cube, random order")
        print()
        print("| order | largest position error | RMS position error |")
        print("| --- | --- | --- |")
        rows = {"the input's (--keep-order)": errors(in_order, scene, index_of), "Morton (default)": errors(read_compressed(sorted_path), scene, index_of)}
        for name, (worst, rms) in rows.items():
            print(f"| {name} | {worst:.3g} | {rms:.3g} |")
        (w0, r0), (w1, r1) = rows.values()
        print(f"| ratio | {w0 / w1:.1f}x | {r0 / r1:.1f}x |")


if __name__ == "__main__":
    main()
