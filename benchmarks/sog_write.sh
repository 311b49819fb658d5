#!/usr/bin/env bash
# Writing a SOG from a .ply: zhf splat against splat-transform 3.7 (-g cpu) on the same scene
# (benchmarks/sog_write.py scene: 10^6 splats of SH degree 3 by default), one run each, wall time
# and CPU seconds (the machine is shared: CPU time is what another job disturbs least) and peak
# memory (/usr/bin/time), then both SOGs read back by zhf and compared with the scene: the
# colour error per SH band over view directions, positions, log-scales and alpha
# (benchmarks/sog_write.py error). Into benchmarks/results/sog_write.txt through
# benchmarks/record.sh; docs/formats.md quotes it. splat-transform clusters on one core for a long
# time (an hour and more at 10^6 splats of degree 3).
#   bash benchmarks/sog_write.sh [SPLATS]
set -euo pipefail
splats=${1:-1000000}
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf
cd "$ZHF_ROOT"
source crosscheck/splat_transform.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 benchmarks/sog_write.py scene "$work/scene.ply" --splats "$splats" --degree 3 --seed 78
zhf_sog="$ZHF_BUILD/cli/zhf splat --in $work/scene.ply --out $work/zhf.sog --quiet"
st_sog="$st -w -q -g cpu $work/scene.ply $work/st.sog"
measure() {
  set -euo pipefail
  echo "## .ply to .sog, one run each (/usr/bin/time: wall seconds, user and system CPU seconds, peak resident KiB)"
  /usr/bin/time -f "zhf splat: %e s wall, %U s user, %S s system, %M KiB" $zhf_sog 2>&1
  /usr/bin/time -f "splat-transform -g cpu: %e s wall, %U s user, %S s system, %M KiB" $st_sog 2>&1
  "$ZHF_BUILD/cli/zhf" splat --in "$work/zhf.sog" --out "$work/zhf_sog.ply" --quiet
  "$ZHF_BUILD/cli/zhf" splat --in "$work/st.sog" --out "$work/splat_transform_sog.ply" --quiet
  echo
  echo "## Each SOG read back by zhf against the scene"
  /usr/bin/python3 benchmarks/sog_write.py error "$work/scene.ply" "$work/zhf_sog.ply" "$work/splat_transform_sog.ply"
}
export -f measure
export zhf_sog st_sog work ZHF_BUILD
out=benchmarks/results/sog_write.txt
[ "$splats" = 1000000 ] || out=benchmarks/results/sog_write_$splats.txt
RECORD_ALL_CORES=1 bash benchmarks/record.sh "$out" \
  "the project's Release build; splat-transform $st_version; $splats splats of SH degree 3" bash -c measure
