"""A synthetic 3D Gaussian Splatting scene, written as the 3DGS tools write it: binary
little-endian .ply with x y z, nx ny nz, f_dc_0..2, f_rest_0..44 (SH degree 3, channel-major),
opacity, scale_0..2 (log scale) and rot_0..3 (quaternion w x y z).

    /usr/bin/python3 examples/make_splats.py OUT.ply [--splats 1000000] [--seed 1] [--ascii]

Splat 0 is a bright, strongly view-dependent splat at the origin (the one
examples/rotate_and_render.py draws); the rest are random.
"""

import argparse

import numpy as np


def properties(degree=3):
    names = ["x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"]
    names += [f"f_rest_{i}" for i in range(3 * ((degree + 1) ** 2 - 1))]
    return names + ["opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"]


def make(splats, seed):
    rng = np.random.default_rng(seed)
    names = properties()
    data = rng.standard_normal((splats, len(names))).astype(np.float32)
    data[:, names.index("nx") : names.index("nz") + 1] = 0
    data[:, names.index("f_rest_0") : names.index("f_rest_44") + 1] *= 0.3
    # Splat 0: red towards +x, green towards +y, blue towards +z (band 1 of each channel).
    data[0] = 0
    data[0, names.index("opacity")] = 4
    data[0, names.index("rot_0")] = 1
    c1 = 0.4886025119029199
    for channel, axis_index in ((0, 2), (1, 0), (2, 1)):
        # 3DGS band 1 is C1 (-y, z, -x): f_rest_{15c + 0, 1, 2} multiply -y, z, -x.
        sign = -1 if axis_index in (0, 2) else 1
        data[0, names.index(f"f_rest_{15 * channel + axis_index}")] = sign * 1.5 / c1
    return names, data


def write(path, names, data, ascii):
    header = ["ply", f"format {'ascii' if ascii else 'binary_little_endian'} 1.0",
              "comment synthetic scene from zhf's examples/make_splats.py", f"element vertex {len(data)}"]
    header += [f"property float {n}" for n in names] + ["end_header"]
    with open(path, "wb") as out:
        out.write(("\n".join(header) + "\n").encode())
        if ascii:
            np.savetxt(out, data, fmt="%.9g")
        else:
            out.write(data.astype("<f4").tobytes())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--splats", type=int, default=1_000_000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--ascii", action="store_true")
    args = parser.parse_args()
    names, data = make(args.splats, args.seed)
    write(args.out, names, data, args.ascii)


if __name__ == "__main__":
    main()
