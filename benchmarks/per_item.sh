#!/usr/bin/env bash
# Per-item rotations, the kernel set's own batch against the SoA blocks (benchmarks/per_item_bench.cc),
# built for each x86-64 level this CPU runs (sse2: baseline, avx2: x86-64-v3, avx512: x86-64-v4),
# each run into benchmarks/results/per_item_<path>.txt through benchmarks/record.sh.
#   bash benchmarks/per_item.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for level in sse2:x86-64 avx2:x86-64-v3 avx512:x86-64-v4; do
  path=${level%%:*} march=${level#*:}
  case $path in
    avx2) grep -q -w avx2 /proc/cpuinfo || continue ;;
    avx512) grep -q -w avx512f /proc/cpuinfo || continue ;;
  esac
  g++ -std=c++17 -O3 -march="$march" -DNDEBUG -Iruntime/include -Igenerated/cpp -Ish/include \
    benchmarks/per_item_bench.cc -o "$work/per_item_$path"
  bash benchmarks/record.sh "benchmarks/results/per_item_$path.txt" "g++ -O3 -march=$march" "$work/per_item_$path"
done
