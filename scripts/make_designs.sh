#!/usr/bin/env bash
# Regenerates the checked-in spherical t-designs (generated/designs/t_T.json) with zhf designs'
# defaults: t = 1..21 and selected larger strengths. Deterministic: the same files on any machine
# and thread count. Usage: bash scripts/make_designs.sh [ZHF_BINARY]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
zhf="${1:-$root/build/cli/zhf}"
mkdir -p "$root/generated/designs"
for t in $(seq 1 21) 25 31; do
  "$zhf" designs --t "$t" --out "$root/generated/designs/t_$t.json"
done
