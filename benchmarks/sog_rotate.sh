#!/usr/bin/env bash
# Turning a 10^6-splat SOG (SH degree 1, splat-transform's 65536-entry palette): zhf splat .sog to
# .sog (positions and orientations per splat, the SH palette once) against zhf turning the scene's
# decoded .ply, farm-bench pairing them run by run with wall time and peak memory; with
# --with-splat-transform also against splat-transform 3.7 turning the SOG (-g cpu: it clusters the
# SH again, about half an hour a run on 2 cores, so one run). Into benchmarks/results/sog_rotate.txt
# through benchmarks/record.sh; docs/performance.md quotes it.
#   bash benchmarks/sog_rotate.sh [--with-splat-transform] [SCENE.sog]
# Without SCENE.sog, splat-transform (pinned, in tools/splat-transform) makes one from a random
# scene first, which takes as long as one of its runs.
set -euo pipefail
with_st=0
[ "${1:-}" = "--with-splat-transform" ] && { with_st=1; shift; }
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf
cd "$ZHF_ROOT"
source crosscheck/splat_transform.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ $# -ge 1 ]; then
  cp "$1" "$work/scene.sog"
else
  /usr/bin/python3 -c "import sys; sys.path.insert(0, 'crosscheck'); from splat_interop import write_scene; write_scene('$work/scene.ply', 1, 1000000, 77)"
  "$st" -w -q -g cpu "$work/scene.ply" "$work/scene.sog"
fi
"$ZHF_BUILD/cli/zhf" splat --in "$work/scene.sog" --out "$work/decoded.ply" --quiet
zhf_sog="$ZHF_BUILD/cli/zhf splat --in $work/scene.sog --out $work/zhf.sog --zyz '0.3 0.5 0.7' --quiet"
zhf_ply="$ZHF_BUILD/cli/zhf splat --in $work/decoded.ply --out $work/zhf.ply --zyz '0.3 0.5 0.7' --quiet"
st_sog="$st -w -q -g cpu $work/scene.sog $work/st.sog -r 10,20,30"
pairs() {
  echo "## A: zhf .sog to .sog, B: zhf turning the decoded .ply (.ply to .ply)"
  farm-bench -n 9 --timeout 900 --vs "$zhf_ply" -- sh -c "exec $zhf_sog"
  if [ "$with_st" = 1 ]; then
    echo
    echo "## A: zhf .sog to .sog, B: splat-transform .sog to .sog (-g cpu), one run"
    farm-bench -n 1 --warmup 0 --timeout 3600 --vs "$st_sog" -- sh -c "exec $zhf_sog"
  fi
}
export -f pairs
export zhf_sog zhf_ply st_sog with_st
RECORD_ALL_CORES=1 bash benchmarks/record.sh benchmarks/results/sog_rotate.txt \
  "the project's Release build; splat-transform $st_version; 10^6 splats of SH degree 1" bash -c pairs
