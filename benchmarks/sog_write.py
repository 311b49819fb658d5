#!/usr/bin/env python3
"""A scene for timing SOG writers, and their SOGs' errors against it.

    sog_write.py scene OUT.ply --splats N --degree D --seed S
    sog_write.py error SCENE.ply DECODED.ply [DECODED.ply ...]

scene: random splats (positions in [-50, 50], f_dc in [-1.5, 1.5], SH in [-0.9, 0.9], opacity
logits in [-4, 4], log-scales in [-8, 3], unit quaternions), each position on the grid SOG stores
(16 bits of sign(p) ln(|p| + 1) between the bounds two corner splats pin), so that a decoded
splat is found again whatever order a writer put it in.

error: each decoded scene (a SOG read back as .ply) matched to SCENE by its grid point (within a
step on each axis: writers round differently), then per
SH band the colour error over 64 view directions (a golden-angle spiral; 3DGS's basis, without
its 0.5 offset and clamp): the RMS and the largest over splats, channels and directions, and the
RMS over all bands together; the RMS error of positions, log-scales and alpha.
"""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "examples"))
from rotate_and_render import basis  # noqa: E402  3DGS's basis, bands 0..3

STEPS = 65535
BOUND = np.log(51.0)  # sign(p) ln(|p| + 1) of p = 50


def names(degree):
    rest = 3 * ((degree + 1) ** 2 - 1)
    return (["x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"] + [f"f_rest_{i}" for i in range(rest)] +
            ["opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"])


def grid_position(t):
    v = -BOUND + 2 * BOUND * t / STEPS
    return np.sign(v) * np.expm1(np.abs(v))


def grid_point(p):
    v = np.sign(p) * np.log1p(np.abs(p))
    return np.rint((v + BOUND) / (2 * BOUND) * STEPS).astype(np.int64)


def scene(out, splats, degree, seed):
    rng = np.random.default_rng(seed)
    cols = names(degree)
    t = rng.integers(0, STEPS + 1, size=(splats, 3))
    t[0], t[1] = 0, STEPS
    keys = (t[:, 0] * (STEPS + 1) + t[:, 1]) * (STEPS + 1) + t[:, 2]
    while len(np.unique(keys)) < splats:  # distinct grid points
        _, first = np.unique(keys, return_index=True)
        again = np.setdiff1d(np.arange(splats), first)
        t[again] = rng.integers(0, STEPS + 1, size=(len(again), 3))
        keys = (t[:, 0] * (STEPS + 1) + t[:, 1]) * (STEPS + 1) + t[:, 2]
    data = np.zeros((splats, len(cols)), dtype=np.float32)
    data[:, 0:3] = grid_position(t)
    data[:, 6:9] = rng.uniform(-1.5, 1.5, (splats, 3))
    rest = 3 * ((degree + 1) ** 2 - 1)
    data[:, 9:9 + rest] = rng.uniform(-0.9, 0.9, (splats, rest))
    data[:, 9 + rest] = rng.uniform(-4, 4, splats)
    data[:, 10 + rest:13 + rest] = rng.uniform(-8, 3, (splats, 3))
    q = rng.uniform(-1, 1, (splats, 4))
    data[:, 13 + rest:] = q / np.linalg.norm(q, axis=1, keepdims=True)
    header = f"ply\nformat binary_little_endian 1.0\nelement vertex {splats}\n"
    header += "".join(f"property float {n}\n" for n in cols) + "end_header\n"
    with open(out, "wb") as f:
        f.write(header.encode())
        f.write(data.astype("<f4").tobytes())


def read_ply(path):
    raw = open(path, "rb").read()
    end = raw.index(b"end_header\n") + len(b"end_header\n")
    cols, count = [], 0
    for line in raw[:end].decode().splitlines():
        if line.startswith("element vertex"):
            count = int(line.split()[2])
        elif line.startswith("property float"):
            cols.append(line.split()[2])
    data = np.frombuffer(raw, dtype="<f4", offset=end, count=count * len(cols)).reshape(count, len(cols)).astype(np.float64)
    return cols, data


def directions(k=64):
    i = np.arange(k)
    z = 1 - (2 * i + 1) / k
    r = np.sqrt(1 - z * z)
    a = np.pi * (3 - np.sqrt(5)) * i
    return np.stack([r * np.cos(a), r * np.sin(a), z], axis=1)


def sh_of(cols, data, degree):
    """(n, 3, (degree + 1)^2): f_dc then f_rest per channel."""
    per = (degree + 1) ** 2 - 1
    sh = np.zeros((len(data), 3, per + 1))
    for c in range(3):
        sh[:, c, 0] = data[:, cols.index(f"f_dc_{c}")]
        for j in range(per):
            sh[:, c, 1 + j] = data[:, cols.index(f"f_rest_{c * per + j}")]
    return sh


def error(scene_path, decoded_paths):
    cols, ref = read_ply(scene_path)
    degree = int(round(np.sqrt(1 + sum(c.startswith("f_rest") for c in cols) / 3))) - 1
    order = np.argsort(key_of(cols, ref))
    y = basis(directions())[:, :(degree + 1) ** 2]  # (64, (degree + 1)^2)
    ref_sh = sh_of(cols, ref, degree)
    sigmoid = lambda v: 1 / (1 + np.exp(-v))
    print("| decoded | splats | " + " | ".join(f"band {l} RMS / max" for l in range(degree + 1)) +
          " | colour RMS | position RMS | log-scale RMS | alpha RMS |")
    print("| --- " * (degree + 7) + "|")
    ref_keys = key_of(cols, ref)
    sorted_keys = ref_keys[order]
    for path in decoded_paths:
        dcols, dec = read_ply(path)
        # Each decoded splat's grid point, to within one step on each axis (writers round apart).
        t = grid_point(dec[:, [dcols.index(a) for a in "xyz"]])
        match = np.full(len(dec), -1)
        for offset in np.ndindex(3, 3, 3):
            u = t + np.array(offset) - 1
            keys = (u[:, 0] * (STEPS + 1) + u[:, 1]) * (STEPS + 1) + u[:, 2]
            at = np.clip(np.searchsorted(sorted_keys, keys), 0, len(order) - 1)
            found = (match < 0) & (sorted_keys[at] == keys)
            match[found] = order[at[found]]
        if len(dec) != len(ref) or (match < 0).any() or len(np.unique(match)) != len(ref):
            sys.exit(f"{path}: its splats are not the scene's (count or grid points differ)")
        diff = sh_of(dcols, dec, degree) - ref_sh[match]
        cells, total = [], np.zeros((len(dec), 3, len(y)))
        for l in range(degree + 1):
            band = diff[:, :, l * l:(l + 1) * (l + 1)] @ y[:, l * l:(l + 1) * (l + 1)].T
            total += band
            cells.append(f"{np.sqrt(np.mean(band ** 2)):.3g} / {np.abs(band).max():.3g}")
        pos = dec[:, [dcols.index(a) for a in "xyz"]] - ref[match][:, [cols.index(a) for a in "xyz"]]
        scl = dec[:, [dcols.index(f"scale_{i}") for i in range(3)]] - ref[match][:, [cols.index(f"scale_{i}") for i in range(3)]]
        alpha = sigmoid(dec[:, dcols.index("opacity")]) - sigmoid(ref[match][:, cols.index("opacity")])
        print(f"| {path.split('/')[-1]} | {len(dec)} | " + " | ".join(cells) +
              f" | {np.sqrt(np.mean(total ** 2)):.3g} | {np.sqrt(np.mean(np.sum(pos ** 2, axis=1))):.3g} | "
              f"{np.sqrt(np.mean(scl ** 2)):.3g} | {np.sqrt(np.mean(alpha ** 2)):.3g} |")


def key_of(cols, data):
    t = grid_point(data[:, [cols.index(a) for a in "xyz"]])
    return (t[:, 0] * (STEPS + 1) + t[:, 1]) * (STEPS + 1) + t[:, 2]


def main(argv):
    if len(argv) >= 2 and argv[0] == "scene":
        opts = dict(zip(argv[2::2], argv[3::2]))
        scene(argv[1], int(opts.get("--splats", 1000000)), int(opts.get("--degree", 3)), int(opts.get("--seed", 1)))
    elif len(argv) >= 3 and argv[0] == "error":
        error(argv[1], argv[2:])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
