#!/usr/bin/env bash
# Highway and xsimd against zhf's own vector code, AVX2 (benchmarks/simd_library_bench.cc): sets up,
# builds the program and writes its output, with the compiler, CPU, commit and date, to
# benchmarks/results/simd_libraries.txt (docs/design.md quotes it) through benchmarks/record.sh. Arguments
# go to the program ([runs]).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf_simd_library_bench
cd "$ZHF_ROOT"
grep -q -w avx2 /proc/cpuinfo || { echo "simd_libraries.sh: this CPU has no AVX2" >&2; exit 1; }
bash benchmarks/record.sh benchmarks/results/simd_libraries.txt "built -O3 -march=x86-64-v3" "$ZHF_BUILD/benchmarks/zhf_simd_library_bench" "$@"
