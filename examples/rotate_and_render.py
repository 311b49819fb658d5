"""Rotates a small synthetic 3DGS scene with zhf splat and draws one splat's view-dependent colour
over the sphere before and after, side by side (equirectangular, SVG), so the colour can be seen
to turn with the scene; also prints the largest colour difference between d before and R d after.

    /usr/bin/python3 examples/rotate_and_render.py ZHF OUT.svg [--axis-angle "0 0 1 1.5707963267948966"]

ZHF is the zhf binary (build/cli/zhf). Splat 0 of examples/make_splats.py is red towards +x,
green towards +y and blue towards +z; after the default quarter turn about z its red faces +y
(an exact axis map: the colours match to the last bit), any other turn to rounding.
"""

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_splats  # noqa: E402

# 3DGS's basis (graphdeco-inria/gaussian-splatting utils/sh_utils.py, eval_sh), degree 3.
C0, C1 = 0.28209479177387814, 0.4886025119029199
C2 = (1.0925484305920792, -1.0925484305920792, 0.31539156525252005, -1.0925484305920792, 0.5462742152960396)
C3 = (-0.5900435899266435, 2.890611442640554, -0.4570457994644658, 0.3731763325901154, -0.4570457994644658,
      1.445305721320277, -0.5900435899266435)


def basis(d):
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    xx, yy, zz = x * x, y * y, z * z
    return np.stack([np.full_like(x, C0), -C1 * y, C1 * z, -C1 * x,
                     C2[0] * x * y, C2[1] * y * z, C2[2] * (2 * zz - xx - yy), C2[3] * x * z, C2[4] * (xx - yy),
                     C3[0] * y * (3 * xx - yy), C3[1] * x * y * z, C3[2] * y * (4 * zz - xx - yy),
                     C3[3] * z * (2 * zz - 3 * xx - 3 * yy), C3[4] * x * (4 * zz - xx - yy), C3[5] * z * (xx - yy),
                     C3[6] * x * (xx - 3 * yy)], axis=-1)


def colour(sh, d):
    """sh: (3, 16) per channel; d: (..., 3) -> (..., 3), 3DGS's 0.5 offset and clamp."""
    return np.clip(basis(d) @ sh.T + 0.5, 0, 1)


def splat_sh(path):
    names = make_splats.properties()
    data = Path(path).read_bytes()
    start = data.index(b"end_header\n") + len(b"end_header\n")
    row = np.frombuffer(data, dtype="<f4", count=len(names), offset=start).astype(np.float64)
    sh = np.zeros((3, 16))
    for c in range(3):
        sh[c, 0] = row[names.index(f"f_dc_{c}")]
        sh[c, 1:] = [row[names.index(f"f_rest_{15 * c + j}")] for j in range(15)]
    return sh


def panel(sh, x0, title, width=360, height=180, step=4):
    cells = [f'<text x="{x0 + width / 2}" y="16" text-anchor="middle" font-family="sans-serif" font-size="13">{title}</text>']
    for py in range(0, height, step):
        for px in range(0, width, step):
            phi = (px + step / 2) / width * 2 * np.pi - np.pi  # -pi at the left, +x at the centre
            theta = (py + step / 2) / height * np.pi            # +z at the top
            d = np.array([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)])
            r, g, b = (255 * colour(sh, d)).astype(int)
            cells.append(f'<rect x="{x0 + px}" y="{24 + py}" width="{step}" height="{step}" fill="rgb({r},{g},{b})"/>')
    return cells


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("zhf")
    parser.add_argument("out")
    parser.add_argument("--axis-angle", default="0 0 1 1.5707963267948966")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as work:
        before, after = f"{work}/before.ply", f"{work}/after.ply"
        names, data = make_splats.make(16, seed=5)
        make_splats.write(before, names, data, ascii=False)
        subprocess.run([args.zhf, "splat", "--in", before, "--out", after, "--axis-angle", args.axis_angle, "--quiet"], check=True)
        sh_before, sh_after = splat_sh(before), splat_sh(after)
    axis_angle = [float(v) for v in args.axis_angle.split()]
    u = np.array(axis_angle[:3]) / np.linalg.norm(axis_angle[:3])
    k = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    r = np.eye(3) + np.sin(axis_angle[3]) * k + (1 - np.cos(axis_angle[3])) * k @ k
    d = np.random.default_rng(1).standard_normal((1000, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    unclamped = lambda sh, v: basis(v) @ sh.T  # noqa: E731
    print(f"max |colour after at R d - colour before at d| = {np.abs(unclamped(sh_after, d @ r.T) - unclamped(sh_before, d)).max():.2g}")
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="740" height="230">']
    svg += panel(sh_before, 0, "splat 0 before: colour seen from each direction")
    svg += panel(sh_after, 380, f"after zhf splat --axis-angle \"{args.axis_angle}\"")
    svg.append('<text x="370" y="222" text-anchor="middle" font-family="sans-serif" font-size="11">'
               "longitude -180..180 degrees (+x at the centre), latitude +z at the top</text>")
    svg.append("</svg>")
    Path(args.out).write_text("\n".join(svg) + "\n")


if __name__ == "__main__":
    main()
