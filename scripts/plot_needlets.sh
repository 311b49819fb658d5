#!/usr/bin/env bash
# Draws docs/needlet_kernels.svg: the needlet of each level shown in docs/frames.md against the
# truncated SH delta of the same top band, each divided by its peak, from `zhf needlets profile`.
# Usage: bash scripts/plot_needlets.sh [ZHF_BINARY]   (needs gnuplot)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
zhf="${1:-$root/build/cli/zhf}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cases=("2 1" "2 2" "2 3" "3 1" "2.4 1")
for c in "${cases[@]}"; do
  read -r b j <<<"$c"
  "$zhf" needlets profile --B "$b" --j "$j" --csv "$work/B${b}_j${j}.csv" >/dev/null
done
cat >"$work/plot.gp" <<GP
set terminal svg size 1200,640 font "sans,11" background "white"
set output "$work/needlet_kernels.svg"
set datafile separator ","
set multiplot layout 2,3 title "Needlets (solid) against the SH delta of the same top band (dashed), each over its peak"
set xlabel "angle from the centre (degrees)"
set grid
set yrange [-0.45:1.05]
GP
for c in "${cases[@]}"; do
  read -r b j <<<"$c"
  cat >>"$work/plot.gp" <<GP
set title "B = $b, j = $j"
set xrange [0:180]
plot "$work/B${b}_j${j}.csv" using 1:2 with lines lw 2 lc rgb "#1f77b4" title "needlet", \
     "" using 1:3 with lines lw 1.5 dt 2 lc rgb "#d62728" title "SH delta"
GP
done
echo "unset multiplot" >>"$work/plot.gp"
gnuplot "$work/plot.gp"
cp "$work/needlet_kernels.svg" "$root/docs/needlet_kernels.svg.tmp"
mv "$root/docs/needlet_kernels.svg.tmp" "$root/docs/needlet_kernels.svg"
echo "wrote docs/needlet_kernels.svg"
