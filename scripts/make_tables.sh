#!/usr/bin/env bash
# Regenerates the checked-in lobe tables generated/lobes/order_N.json, each with the command
# recorded in its provenance. Orders 3..8 take seconds to minutes; 9..12 up to an hour each.
# Usage: scripts/make_tables.sh [ORDER...]   (default: 3..12, 16, 32); ZHF_THREADS sets the thread count.
# Seconds on 2 threads: orders 3..8: 0.1, 0.5, 5, 22, 46, 330; 9: 425; 10: 1333; 11: 852; 12: 580.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$ZHF_ROOT"

table_command() {
  local order=$1
  local extra=""
  # Order 6 still reaches its zero target with every band's condition <= 8, which lowers its
  # float error (2.4e-6 to 1.6e-6); at 7 and 8 that bound costs too many zeros (README,
  # "Numerical limits").
  [ "$order" -eq 6 ] && extra=" --max-condition 8"
  # Above order 8 a local-search kick costs seconds (above 10, most of a minute); stop after
  # fewer fruitless kicks.
  [ "$order" -gt 8 ] && [ "$order" -le 10 ] && extra=" --local-search-stall 25"
  [ "$order" -gt 10 ] && [ "$order" -le 12 ] && extra=" --local-search-stall 5"
  # Orders 16 and 32 serve the runtime path's numerical limits, not speed: a small GA and one
  # descent (16: about 7 minutes); 32 stops at a time limit, so its result depends on speed.
  [ "$order" -eq 16 ] && extra=" --population 24 --generations 10 --stall 5 --local-search-stall 0"
  [ "$order" -eq 32 ] && extra=" --population 8 --generations 2 --stall 1 --local-search-stall 0 --time-limit 240"
  echo "optimize --order $order --seed 1$extra --out generated/lobes/order_$order.json"
}

orders=("$@")
[ ${#orders[@]} -gt 0 ] || orders=(3 4 5 6 7 8 9 10 11 12 16 32)
for order in "${orders[@]}"; do
  echo "== order $order"
  start=$(date +%s)
  # shellcheck disable=SC2046
  "$ZHF_BUILD/cli/zhf" $(table_command "$order") --threads "${ZHF_THREADS:-0}" --quiet
  echo "   $(( $(date +%s) - start )) s"
done
