#!/usr/bin/env bash
# Highway and xsimd against zhf's own vector code, AVX2 (bench/simd_library_bench.cc): sets up,
# builds the program and writes its output, with the compiler, CPU, commit and date, to
# bench/results/simd_libraries.txt (docs/design.md quotes it). Arguments go to the program
# ([runs]). Run on one core (taskset -c 1) where the machine has two or more.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf_simd_library_bench
cd "$ZHF_ROOT"
grep -q -w avx2 /proc/cpuinfo || { echo "simd_libraries.sh: this CPU has no AVX2" >&2; exit 1; }
pin=()
[ "$(nproc)" -ge 2 ] && pin=(taskset -c 1)
cpu=$(grep -m1 "model name" /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')
isa=$(grep -q -w avx512f /proc/cpuinfo && echo "AVX2, AVX-512" || echo "AVX2, no AVX-512")
tree=$(git diff --quiet HEAD -- && echo "clean tree" || echo "modified tree")
out=bench/results/simd_libraries.txt
tmp=$(mktemp "$out.XXXXXX")
trap 'rm -f "$tmp"' EXIT
{
  echo "# bash bench/simd_libraries.sh $*: ${pin[*]} build/bench/zhf_simd_library_bench $*, built -O3 -march=x86-64-v3"
  echo "# $(g++ --version | head -1); CPU: $cpu ($isa), $(nproc) cores; commit $(git rev-parse --short HEAD) ($tree); $(date -u +%F)"
  "${pin[@]}" "$ZHF_BUILD/bench/zhf_simd_library_bench" "$@"
} > "$tmp"
mv "$tmp" "$out"
trap - EXIT
cat "$out"
