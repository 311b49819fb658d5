#!/usr/bin/env bash
# The position error Morton order saves in a compressed .ply (benchmarks/splat_morton.py): sets up and
# builds zhf, then writes the table to benchmarks/results/splat_morton.txt through benchmarks/record.sh;
# docs/formats.md quotes it. Argument: splats (default 200000).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf
cd "$ZHF_ROOT"
RECORD_ALL_CORES=1 bash benchmarks/record.sh benchmarks/results/splat_morton.txt "the project's Release build" \
  /usr/bin/python3 benchmarks/splat_morton.py "$ZHF_BUILD/cli/zhf" --splats "${1:-200000}"
