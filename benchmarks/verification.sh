#!/usr/bin/env bash
# The measured tables of docs/verification.md, in one run: the largest error per order and
# precision over random rotations (benchmarks/numerical_limits.cc) and the drift of a long chain of
# small rotations (benchmarks/chain_bench.cc), each into benchmarks/results/verification/ through
# benchmarks/record.sh; then the page's table blocks (benchmarks/performance_tables.py). Refuses a modified
# tree. About a minute.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/clean_tree.sh" verification.sh
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf_numerical_limits zhf_chain_bench
mkdir -p benchmarks/results/verification
export RECORD_ALL_CORES=1  # errors, not times
bash benchmarks/record.sh benchmarks/results/verification/numerical_limits.txt "the Release build" "$ZHF_BUILD/benchmarks/zhf_numerical_limits" > /dev/null
bash benchmarks/record.sh benchmarks/results/verification/chain.txt "the Release build" "$ZHF_BUILD/benchmarks/zhf_chain_bench" > /dev/null
/usr/bin/python3 benchmarks/performance_tables.py --update docs/verification.md
