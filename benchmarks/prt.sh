#!/usr/bin/env bash
# The figures of docs/frames.md's PRT section, in one run: the exact reference's convergence
# (benchmarks/prt_reference.cc) into benchmarks/results/prt/reference.txt, then zhf needlets prt for every
# scene and transfer (K = 4 .. 1024, bands 0..31) into benchmarks/results/prt/<scene>_<transfer>.txt,
# each through benchmarks/record.sh; then the plots (scripts/plot_frames.sh) and the tables of
# docs/frames.md (benchmarks/performance_tables.py). Refuses a modified tree.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/clean_tree.sh" prt.sh
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf zhf_prt_reference
mkdir -p benchmarks/results/prt
export RECORD_ALL_CORES=1  # vertices run on every core; the figures are errors, not times
bash benchmarks/record.sh benchmarks/results/prt/reference.txt "the Release build" "$ZHF_BUILD/benchmarks/zhf_prt_reference" > /dev/null
for scene in sphere corner spheres; do
  for transfer in diffuse glossy; do
    bash benchmarks/record.sh "benchmarks/results/prt/${scene}_$transfer.txt" "the Release build" \
      "$ZHF_BUILD/cli/zhf" needlets prt --quiet --scene "$scene" --transfer "$transfer" --kept 4,9,16,36,64,144,256,576,1024 > /dev/null
  done
done
bash scripts/plot_frames.sh "$ZHF_BUILD/cli/zhf"
/usr/bin/python3 benchmarks/performance_tables.py --update docs/frames.md
