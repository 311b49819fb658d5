#!/usr/bin/env bash
# The position error Morton order saves in a compressed .ply (bench/splat_morton.py): sets up and
# builds zhf, then writes the table to bench/results/splat_morton.txt through bench/record.sh;
# docs/formats.md quotes it. Argument: splats (default 200000).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf
cd "$ZHF_ROOT"
RECORD_ALL_CORES=1 bash bench/record.sh bench/results/splat_morton.txt "the project's Release build" \
  /usr/bin/python3 bench/splat_morton.py "$ZHF_BUILD/cli/zhf" --splats "${1:-200000}"
