"""zhf splat against @playcanvas/splat-transform on the same scene: the rotation splat-transform
applied (fitted from its positions), then zhf splat with that matrix, compared field by field:
positions, orientations (up to sign), log-scales, colour, opacity and SH per band, the largest
absolute difference of each. Both write .ply, whatever the scene's format.

    /usr/bin/python3 crosscheck/splat_crosscheck.py SCENE SPLAT_TRANSFORM ZHF [--rotate 10,20,30] [--glb]

SCENE: a binary 3DGS .ply (examples/make_splats.py), a .compressed.ply or a .splat (zhf splat
--in X.ply --out X.compressed.ply); SPLAT_TRANSFORM: its executable (npm install @playcanvas/splat-transform); ZHF: the zhf
binary.
--glb: splat-transform writes its result as .glb (it does not read .glb), which zhf reads; then
both write the unrotated scene as .glb and their attributes are compared as stored.
"""

import argparse
import json
import struct
import subprocess
import tempfile
from pathlib import Path

import numpy as np


def read_ply(path):
    """A binary little-endian PLY of scalar float/int properties, as {name: array}."""
    data = Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    count = next(int(l.split()[2]) for l in header if l.startswith("element vertex"))
    types = {"float": "<f4", "double": "<f8", "int": "<i4", "uint": "<u4", "uchar": "u1", "char": "i1"}
    dtype = [(l.split()[2], types[l.split()[1]]) for l in header if l.startswith("property")]
    records = np.frombuffer(data, dtype=dtype, count=count, offset=end)
    return {name: records[name].astype(np.float64) for name, _ in dtype}


def read_glb(path):
    """A .glb's float attributes of its first primitive, as {attribute: array of rows}."""
    data = Path(path).read_bytes()
    json_bytes = struct.unpack_from("<I", data, 12)[0]
    gltf = json.loads(data[20:20 + json_bytes])
    bin_at = 20 + json_bytes + 8
    widths = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}
    out = {}
    for name, index in gltf["meshes"][0]["primitives"][0]["attributes"].items():
        accessor = gltf["accessors"][index]
        if accessor["componentType"] != 5126:
            continue
        view = gltf["bufferViews"][accessor["bufferView"]]
        width = widths[accessor["type"]]
        at = bin_at + view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
        out[name] = np.frombuffer(data, dtype="<f4", count=accessor["count"] * width, offset=at).reshape(-1, width).astype(np.float64)
    return out


def compare_glb(a, b):
    """Attributes of two .glb files of one scene, as stored (rotations up to sign)."""
    print("| .glb attribute | max abs difference, zhf vs splat-transform |")
    print("| --- | --- |")
    for name in sorted(set(a) | set(b)):
        if name not in a or name not in b:
            print(f"| {name} | only in {'zhf' if name in a else 'splat-transform'} |")
            continue
        x, y = a[name], b[name]
        if name.endswith("ROTATION"):
            x = x / np.linalg.norm(x, axis=1, keepdims=True)
            y = y / np.linalg.norm(y, axis=1, keepdims=True)
            y = y * np.sign(np.sum(x * y, axis=1, keepdims=True))
        print(f"| {name} | {np.abs(x - y).max():.3g} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene")
    parser.add_argument("splat_transform")
    parser.add_argument("zhf")
    parser.add_argument("--rotate", default="10,20,30", help="splat-transform's -r (Euler degrees, its axes)")
    parser.add_argument("--glb", action="store_true", help="splat-transform writes .glb, zhf reads it")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as work:
        peer_out, zhf_out = f"{work}/peer.ply", f"{work}/zhf.ply"
        if args.glb:
            subprocess.run([args.splat_transform, args.scene, "-r", args.rotate, f"{work}/peer.glb"], check=True, capture_output=True)
            subprocess.run([args.zhf, "splat", "--in", f"{work}/peer.glb", "--out", peer_out, "--identity", "--quiet"], check=True)
            subprocess.run([args.splat_transform, args.scene, f"{work}/peer0.glb"], check=True, capture_output=True)
            subprocess.run([args.zhf, "splat", "--in", args.scene, "--out", f"{work}/zhf0.glb", "--identity", "--quiet"], check=True)
            compare_glb(read_glb(f"{work}/zhf0.glb"), read_glb(f"{work}/peer0.glb"))
        else:
            subprocess.run([args.splat_transform, args.scene, "-r", args.rotate, peer_out], check=True, capture_output=True)
        if args.scene.endswith(".ply") and not args.scene.endswith(".compressed.ply"):
            a = read_ply(args.scene)
        else:  # decoded by zhf (zhf and splat-transform decode these formats alike: docs/formats.md)
            subprocess.run([args.zhf, "splat", "--in", args.scene, "--out", f"{work}/in.ply", "--identity", "--quiet"], check=True)
            a = read_ply(f"{work}/in.ply")
        b = read_ply(peer_out)
        p_in = np.stack([a["x"], a["y"], a["z"]], axis=1)
        p_out = np.stack([b["x"], b["y"], b["z"]], axis=1)
        r = np.linalg.lstsq(p_in, p_out, rcond=None)[0].T  # p_out = R p_in
        u, _, vt = np.linalg.svd(r)
        r = u @ vt  # the nearest orthogonal matrix
        print(f"splat-transform -r {args.rotate} applied, in the file's axes:\n{np.array2string(r, precision=6)}")
        subprocess.run([args.zhf, "splat", "--in", args.scene, "--out", zhf_out, "--quiet",
                        "--matrix", " ".join(f"{x:.17g}" for x in r.ravel())], check=True)
        c = read_ply(zhf_out)
    print("| field | max abs difference, zhf vs splat-transform |")
    print("| --- | --- |")
    print(f"| positions | {max(np.abs(c[k] - b[k]).max() for k in 'xyz'):.3g} |")
    qc = np.stack([c[f"rot_{i}"] for i in range(4)], axis=1)
    qb = np.stack([b[f"rot_{i}"] for i in range(4)], axis=1)
    qc /= np.linalg.norm(qc, axis=1, keepdims=True)
    qb /= np.linalg.norm(qb, axis=1, keepdims=True)
    sign = np.sign(np.sum(qc * qb, axis=1, keepdims=True))
    print(f"| orientations (unit, up to sign) | {np.abs(qc - sign * qb).max():.3g} |")
    print(f"| log-scales | {max(np.abs(c[f'scale_{i}'] - b[f'scale_{i}']).max() for i in range(3)):.3g} |")
    print(f"| colour (f_dc) | {max(np.abs(c[f'f_dc_{i}'] - b[f'f_dc_{i}']).max() for i in range(3)):.3g} |")
    print(f"| opacity | {np.abs(c['opacity'] - b['opacity']).max():.3g} |")
    for band, (first, last) in enumerate([(0, 3), (3, 8), (8, 15)], start=1):
        if f"f_rest_{15 * 2 + last - 1}" not in c:
            break
        diff = max(np.abs(c[f"f_rest_{15 * ch + j}"] - b[f"f_rest_{15 * ch + j}"]).max() for ch in range(3) for j in range(first, last))
        print(f"| SH band {band} | {diff:.3g} |")


if __name__ == "__main__":
    main()
