#!/usr/bin/env bash
# Writing a SOG from a .ply: zhf splat against splat-transform 3.7 (-g cpu) on the same scene
# (benchmarks/sog_write.py scene: 10^6 splats of SH degree 3 by default), one run each, wall time
# and CPU seconds (the machine is shared: CPU time is what another job disturbs least) and peak
# memory (/usr/bin/time), then each finished SOG read back by zhf and compared with the scene: the
# colour error per SH band over view directions, positions, log-scales and alpha
# (benchmarks/sog_write.py error). Into benchmarks/results/sog_write.txt through
# benchmarks/record.sh; docs/formats.md quotes it.
# splat-transform's CPU k-means assigns each splat through a k-d tree over the palette, which in
# 45 dimensions prunes little: at 10^6 splats (65 536 entries) it runs for many hours. It is
# stopped after ST_LIMIT seconds (default 3600); the file then says so and lists the stages it
# finished, and its time is a lower bound.
#   [ST_LIMIT=SECONDS] bash benchmarks/sog_write.sh [SPLATS]
set -euo pipefail
splats=${1:-1000000}
st_limit=${ST_LIMIT:-3600}
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf
cd "$ZHF_ROOT"
source crosscheck/splat_transform.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Its own copy of zhf: a rebuild during splat-transform's long run cannot change what decodes.
zhf="$work/zhf"
cp "$ZHF_BUILD/cli/zhf" "$zhf"
/usr/bin/python3 benchmarks/sog_write.py scene "$work/scene.ply" --splats "$splats" --degree 3 --seed 78
zhf_sog="$zhf splat --in $work/scene.ply --out $work/zhf.sog --quiet"
st_sog="$st -w -g cpu $work/scene.ply $work/st.sog"
measure() {
  set -euo pipefail
  echo "## .ply to .sog, one run each (/usr/bin/time: wall seconds, user and system CPU seconds, peak resident KiB)"
  /usr/bin/time -f "zhf splat: %e s wall, %U s user, %S s system, %M KiB" $zhf_sog 2>&1
  local decoded=("$work/zhf_sog.ply")
  local status=0
  /usr/bin/time -o "$work/st_time" -f "%e s wall, %U s user, %S s system, %M KiB" \
    timeout "$st_limit" $st_sog > "$work/st_log" 2>&1 || status=$?
  if [ "$status" = 0 ]; then
    echo "splat-transform -g cpu: $(tail -1 "$work/st_time")"
    decoded+=("$work/splat_transform_sog.ply")
  elif [ "$status" = 124 ]; then
    echo "splat-transform -g cpu: stopped after $st_limit s (ST_LIMIT), unfinished: $(tail -1 "$work/st_time")"
    echo "its log up to then:"
    sed 's/^/    /' "$work/st_log"
  else
    cat "$work/st_log" >&2
    return "$status"
  fi
  "$zhf" splat --in "$work/zhf.sog" --out "$work/zhf_sog.ply" --quiet
  [ ! -e "$work/st.sog" ] || "$zhf" splat --in "$work/st.sog" --out "$work/splat_transform_sog.ply" --quiet
  echo
  echo "## Each finished SOG read back by zhf against the scene"
  /usr/bin/python3 benchmarks/sog_write.py error "$work/scene.ply" "${decoded[@]}"
}
export -f measure
export zhf zhf_sog st_sog st_limit work
out=benchmarks/results/sog_write.txt
[ "$splats" = 1000000 ] || out=benchmarks/results/sog_write_$splats.txt
RECORD_ALL_CORES=1 bash benchmarks/record.sh "$out" \
  "the project's Release build; splat-transform $st_version, stopped after $st_limit s; $splats splats of SH degree 3" bash -c measure
