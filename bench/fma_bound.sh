#!/usr/bin/env bash
# How far each instruction-set path is from its arithmetic bound (bench/fma_bound_bench.cc): sets
# up, builds the program in the Release build (no -march: zhf::dispatch runs each path this CPU
# has) and writes its tables to bench/results/fma_bound.txt through bench/record.sh, which
# docs/performance.md quotes. Arguments go to the program (default --reps 61).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf_fma_bound_bench
cd "$ZHF_ROOT"
[ $# -gt 0 ] || set -- --reps 61
bash bench/record.sh bench/results/fma_bound.txt "the project's Release build (no -march; zhf::dispatch runs each path)" \
  "$ZHF_BUILD/bench/zhf_fma_bound_bench" "$@"
