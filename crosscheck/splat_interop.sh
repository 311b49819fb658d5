#!/usr/bin/env bash
# zhf splat and @playcanvas/splat-transform on each other's files, every format and SH degree
# 0..4 both ways (crosscheck/splat_interop.py): sets up and builds zhf, installs splat-transform,
# pinned, into the project's own tools/splat-transform (never globally), and writes the table to
# benchmarks/results/splat_interop.txt through benchmarks/record.sh; docs/formats.md quotes it.
# Argument: splats per scene (default 2000).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf
cd "$ZHF_ROOT"
source crosscheck/splat_transform.sh
RECORD_ALL_CORES=1 bash benchmarks/record.sh benchmarks/results/splat_interop.txt "the project's Release build; splat-transform $st_version" \
  /usr/bin/python3 crosscheck/splat_interop.py "$ZHF_BUILD/cli/zhf" "$st" --splats "${1:-2000}"
