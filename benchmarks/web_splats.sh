#!/usr/bin/env bash
# zhf's WebAssembly module against @playcanvas/splat-transform 3.7's SH rotation and against native
# zhf on one thread, 10^6 splats of each SH degree 1..4, in one run of benchmarks/web_splats.mjs, into
# benchmarks/results/web/web_splats.txt through benchmarks/record.sh (pinned to one core); docs/web.md's
# table is made from it (python3 benchmarks/performance_tables.py --update docs/web.md). From a clean
# tree only.
#   bash benchmarks/web_splats.sh [splats] [runs]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/clean_tree.sh" web_splats.sh
bash scripts/setup_web.sh
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf_web_package zhf_web_splats_native
source crosscheck/splat_transform.sh
mkdir -p benchmarks/results/web
bash benchmarks/record.sh benchmarks/results/web/web_splats.txt "Release; WebAssembly built by emscripten $(em++ --version | head -1 | grep -o '[0-9][0-9.]*' | tail -1) -O3 -msimd128" \
  node benchmarks/web_splats.mjs "$ZHF_BUILD/web/package" "$st_dir/node_modules/@playcanvas/splat-transform" \
  "$ZHF_BUILD/benchmarks/zhf_web_splats_native" "${1:-1000000}" "${2:-7}"
python3 benchmarks/performance_tables.py --update docs/web.md
