#!/usr/bin/env bash
# The measured tables of docs/verification.md, in one run: the largest error per order and
# precision over random rotations (bench/numerical_limits.cc) and the drift of a long chain of
# small rotations (bench/chain_bench.cc), each into bench/results/verification/ through
# bench/record.sh; then the page's table blocks (bench/performance_tables.py). Refuses a modified
# tree. About a minute.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/clean_tree.sh" verification.sh
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf_numerical_limits zhf_chain_bench
mkdir -p bench/results/verification
export RECORD_ALL_CORES=1  # errors, not times
bash bench/record.sh bench/results/verification/numerical_limits.txt "the Release build" "$ZHF_BUILD/bench/zhf_numerical_limits" > /dev/null
bash bench/record.sh bench/results/verification/chain.txt "the Release build" "$ZHF_BUILD/bench/zhf_chain_bench" > /dev/null
/usr/bin/python3 bench/performance_tables.py --update docs/verification.md
