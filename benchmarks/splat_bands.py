"""What cutting SH bands costs and saves: zhf splat --sh-degree K for K = 0..4 on degree-4 scenes,
into .ply and .spz, with the output's bytes, the dropped energy (relative L2, as zhf analyze
measures it) and the largest change of one splat's colour over 256 view directions, as zhf splat
reports them.

    python3 benchmarks/splat_bands.py ZHF [--splats N] > table.md

Scenes (seeded): "flat", every band's coefficients uniform in [-0.9, 0.9]; "decaying", band l's
scaled by 0.4^l, as trained scenes' higher bands are quieter.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from splat_interop import write_scene

SCENES = {"flat": lambda band: 1.0, "decaying": lambda band: 0.4 ** band}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("zhf")
    parser.add_argument("--splats", type=int, default=100000)
    a = parser.parse_args()
    print(f"zhf splat --sh-degree K on {a.splats} random degree-4 splats per scene (seeded)")
    print()
    print("| scene | format | SH degree kept | bytes | dropped energy | largest colour change |")
    print("| --- | --- | --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as tmp:
        for name, band_scale in SCENES.items():
            scene = str(Path(tmp) / f"{name}.ply")
            write_scene(scene, 4, a.splats, 7, band_scale)
            for fmt in (".ply", ".spz"):
                for kept in range(4, -1, -1):
                    out = str(Path(tmp) / ("out" + fmt))
                    result = subprocess.run([a.zhf, "splat", "--in", scene, "--out", out, "--sh-degree", str(kept)],
                                            capture_output=True, text=True, check=True)
                    m = re.search(r"dropped energy (\S+) .* largest colour change (\S+) over", result.stdout)
                    if kept == 4:  # nothing dropped, nothing printed
                        energy, colour = "0", "0"
                    elif m:
                        energy, colour = m.group(1), m.group(2)
                    else:
                        sys.exit(f"splat_bands: --sh-degree {kept} printed no dropped figures:\n{result.stdout}")
                    print(f"| {name} | {fmt} | {kept} | {os.path.getsize(out)} | {energy} | {colour} |")


if __name__ == "__main__":
    main()
