#!/usr/bin/env bash
# Every figure of docs/performance.md, measured in one run on this machine:
#   bash benchmarks/performance.sh
# Sets up, builds the Release build (no -march, as users get zhf) and build-x86-64-v3/
# (-march=x86-64-v3), then writes into benchmarks/results/<isa>/ (avx512, avx2 or sse2: the best this
# CPU runs), each file with the command, compiler, CPU, commit, tree and date (benchmarks/record.sh):
#   peers_*.txt           single rotations, zhf's paths against every peer (benchmarks/peers.sh):
#                         orders 2..8, 16, 32, 64 and, in *_order128.txt, 128; both builds
#   fma_bound.txt         each instruction set's distance from its arithmetic bound, orders 2..128
#   bulk_*.txt            one rotation for many vectors (3DGS layout, planar) against a copy, and
#                         many rotations in SoA layout (benchmarks/bulk_bench.cc); both builds
#   splat_builds.txt      zhf splat on 10^6 degree-3 splats, the two builds paired run by run
#   python_builds*.txt    the Python module of the two builds, paired call by call, both ways round
#   bench.json            zhf bench (every method and scenario, time and error), whose plots are
#                         drawn into docs/bench.svg, docs/bench_scenarios.svg, docs/bench_scaling.svg
# then benchmarks/performance_tables.py rewrites the table blocks of docs/performance.md (and the
# bench tables of docs/frames.md and docs/products.md) from their files (a test checks they match). Refuses to run from a modified tree: the files name the commit they measured. About 40
# minutes on 2 cores from a clean clone (the two builds take most of it). Keep the machine idle.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/clean_tree.sh" performance.sh
isa=$(grep -q -w avx512f /proc/cpuinfo && echo avx512 || { grep -q -w avx2 /proc/cpuinfo && echo avx2 || echo sse2; })
results=benchmarks/results/$isa
mkdir -p "$results"

source benchmarks/both_builds.sh zhf
for build in "$ZHF_BUILD" "$ZHF_BUILD_V3"; do
  cmake --build "$build" -j "$ZHF_JOBS" --target zhf_dispatch zhf_bulk_bench zhf_fma_bound_bench _zhf
done
default="the Release build (-O3, no -march)" v3="the Release build with -march=x86-64-v3"

# Single rotations per path and per peer.
RESULTS=$results bash benchmarks/peers.sh

# The arithmetic bound, through zhf::dispatch (every path this CPU runs).
bash benchmarks/record.sh "$results/fma_bound.txt" "$default; zhf::dispatch runs each path" \
  "$ZHF_BUILD/benchmarks/zhf_fma_bound_bench" --reps 61 > /dev/null

# Bulk and SoA: 2^20 items at order 4 and 2^18 at 8, then counts that are no power of two.
export RECORD_ALL_CORES=1  # from here on some rows run on two threads
bash benchmarks/record.sh "$results/bulk_default_build.txt" "$default" "$ZHF_BUILD/benchmarks/zhf_bulk_bench" > /dev/null
bash benchmarks/record.sh "$results/bulk_x86_64_v3.txt" "$v3" "$ZHF_BUILD_V3/bench/zhf_bulk_bench" > /dev/null
bash benchmarks/record.sh "$results/bulk_x86_64_v3_odd_counts.txt" "$v3" "$ZHF_BUILD_V3/bench/zhf_bulk_bench" 1049176 > /dev/null

# zhf splat, the two builds paired run by run (farm-bench), 15 runs each way round.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
/usr/bin/python3 examples/make_splats.py "$work/scene.ply" > /dev/null
splat_default="$ZHF_BUILD/cli/zhf splat --in $work/scene.ply --out $work/default.ply --zyz '0.3 0.5 0.7'"
splat_v3="$ZHF_BUILD_V3/cli/zhf splat --in $work/scene.ply --out $work/v3.ply --zyz '0.3 0.5 0.7'"
both() {
  echo "## A: the default build, B: x86-64-v3"
  farm-bench -n 15 --timeout 900 --vs "$splat_v3" -- sh -c "exec $splat_default"
  echo
  echo "## A: x86-64-v3, B: the default build"
  farm-bench -n 15 --timeout 900 --vs "$splat_default" -- sh -c "exec $splat_v3"
}
export -f both
export splat_default splat_v3
bash benchmarks/record.sh "$results/splat_builds.txt" \
  "zhf splat, 10^6 degree-3 splats, $default against -march=x86-64-v3" bash -c both > /dev/null

# The Python module of the two builds, both ways round (one thread).
export RECORD_ALL_CORES=0
python_default=${ZHF_BUILD#$ZHF_ROOT/}/python python_v3=${ZHF_BUILD_V3#$ZHF_ROOT/}/python
bash benchmarks/record.sh "$results/python_builds.txt" "$default against -march=x86-64-v3" \
  /usr/bin/python3 benchmarks/python_builds_bench.py "$python_default" "$python_v3" --reps 15 > /dev/null
bash benchmarks/record.sh "$results/python_builds_swapped.txt" "-march=x86-64-v3 against $default" \
  /usr/bin/python3 benchmarks/python_builds_bench.py "$python_v3" "$python_default" --reps 15 > /dev/null

# Every method side by side (the Release build: zhf_dispatch rows run this CPU's path), and the plots.
export RECORD_ALL_CORES=1
bash benchmarks/record.sh "$results/bench.txt" "$default" \
  "$ZHF_BUILD/cli/zhf" bench --out "$results/bench.json" --plot docs/bench.svg > /dev/null

/usr/bin/python3 benchmarks/performance_tables.py --update docs/performance.md docs/frames.md docs/products.md
echo "performance.sh: wrote $results/ and docs/bench*.svg, and the docs' table blocks that name $results"
