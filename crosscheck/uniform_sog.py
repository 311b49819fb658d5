"""A uniform scene for tests/data/uniform.sog: 200 000 splats of SH degree 3 with one scale,
colour, opacity, rotation and SH, at the four corners of a unit square (z = 1), as a binary .ply.
splat-transform's SOG of it has images of a few dozen bytes that decode to 448 x 448 texels each:
a valid file far past any expansion ratio a reader might assume. crosscheck/uniform_sog.sh runs it.
With --deflate IN OUT: IN's entries deflated into OUT, in order, dated 1980-01-01.
"""
import struct
import sys
import zipfile

SPLATS = 200_000
REST = [0.25 * (-1) ** j / (1 + j // 15) for j in range(45)]


def deflate(source, target):
    with zipfile.ZipFile(source) as zin, zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as zout:
        for entry in zin.infolist():
            zout.writestr(zipfile.ZipInfo(entry.filename, (1980, 1, 1, 0, 0, 0)), zin.read(entry), zipfile.ZIP_DEFLATED)


def main():
    if sys.argv[1] == "--deflate":
        deflate(sys.argv[2], sys.argv[3])
        return
    names = ["x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2"] + [f"f_rest_{j}" for j in range(45)]
    names += ["opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"]
    header = f"ply\nformat binary_little_endian 1.0\nelement vertex {SPLATS}\n"
    header += "".join(f"property float {n}\n" for n in names) + "end_header\n"
    out = bytearray(header.encode())
    for i in range(SPLATS):
        row = [float(i % 2), float(i // 2 % 2), 1.0, 0.5, -0.25, 0.75] + REST + [2.0, -3.0, -3.0, -3.0, 1.0, 0.0, 0.0, 0.0]
        out += struct.pack(f"<{len(row)}f", *row)
    with open(sys.argv[1], "wb") as f:
        f.write(out)


if __name__ == "__main__":
    main()
