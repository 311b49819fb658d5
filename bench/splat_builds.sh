#!/usr/bin/env bash
# zhf splat as users get it (the Release build, no -march) against the same CLI built with
# -DCMAKE_CXX_FLAGS=-march=x86-64-v3 (in build-x86-64-v3/): a synthetic 10^6-splat degree-3 scene
# (examples/make_splats.py) rotated by both, farm-bench pairing them run by run, each order once,
# on all cores, into bench/results/splat_builds.txt through bench/record.sh; docs/performance.md
# quotes it. Argument: runs per order (default 15).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/both_builds.sh" zhf
runs=${1:-15}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 examples/make_splats.py "$work/scene.ply"
default="$ZHF_BUILD/cli/zhf splat --in $work/scene.ply --out $work/default.ply --zyz '0.3 0.5 0.7'"
other="$ZHF_BUILD_V3/cli/zhf splat --in $work/scene.ply --out $work/v3.ply --zyz '0.3 0.5 0.7'"
both() {
  echo "## A: the default build, B: x86-64-v3"
  farm-bench -n "$runs" --timeout 900 --vs "$other" -- sh -c "exec $default"
  echo
  echo "## A: x86-64-v3, B: the default build"
  farm-bench -n "$runs" --timeout 900 --vs "$default" -- sh -c "exec $other"
}
export -f both
export default other runs
RECORD_ALL_CORES=1 bash bench/record.sh bench/results/splat_builds.txt \
  "zhf splat, 10^6 degree-3 splats, the Release build (no -march) against -march=x86-64-v3" bash -c both
