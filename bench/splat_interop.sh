#!/usr/bin/env bash
# zhf splat and @playcanvas/splat-transform on each other's files, every format and SH degree
# 0..4 both ways (bench/splat_interop.py): sets up and builds zhf, installs splat-transform,
# pinned, into the project's own tools/splat-transform (never globally), and writes the table to
# bench/results/splat_interop.txt through bench/record.sh; docs/formats.md quotes it.
# Argument: splats per scene (default 2000).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf
cd "$ZHF_ROOT"
st_version=3.7.0
st_dir=tools/splat-transform
if ! grep -qs "\"version\": \"$st_version\"" "$st_dir/node_modules/@playcanvas/splat-transform/package.json"; then
  echo "zhf bench: installing @playcanvas/splat-transform@$st_version into $st_dir"
  mkdir -p "$st_dir"
  npm install --prefix "$st_dir" --no-audit --no-fund --loglevel=error "@playcanvas/splat-transform@$st_version" > /dev/null
fi
RECORD_ALL_CORES=1 bash bench/record.sh bench/results/splat_interop.txt "the project's Release build; splat-transform $st_version" \
  /usr/bin/python3 bench/splat_interop.py "$ZHF_BUILD/cli/zhf" "$st_dir/node_modules/.bin/splat-transform" --splats "${1:-2000}"
