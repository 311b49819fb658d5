#!/usr/bin/env bash
# Draws the plots of docs/frames.md:
#   docs/needlet_kernels.svg  needlets against the truncated SH delta of the same top band, each
#                             over its peak (zhf needlets profile);
#   docs/projection.svg       projection error per sample count of designs, Gauss rules and
#                             equal-angle grids (zhf project --compare);
#   docs/prt_error.svg        shading error of SH and needlets against coefficients kept per
#                             vertex, three scenes (zhf needlets prt);
#   docs/prt_images.svg       the three spheres' ground shaded exactly, by SH and by needlets at
#                             64 coefficients a vertex, and both errors.
# Usage: bash scripts/plot_frames.sh [ZHF_BINARY]   (needs gnuplot)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
zhf="${1:-$root/build/cli/zhf}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cases=("2 1" "2 2" "2 3" "3 1" "2.4 1")
for c in "${cases[@]}"; do
  read -r b j <<<"$c"
  "$zhf" needlets profile --B "$b" --level "$j" --out "$work/B${b}_j${j}.csv" >/dev/null
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

"$zhf" project --compare --order 8 --csv "$work/projection.csv" >/dev/null
for family in design gauss grid; do grep "^$family," "$work/projection.csv" >"$work/$family.csv" || true; done
cat >"$work/projection.gp" <<GP
set terminal svg size 1000,420 font "sans,11" background "white"
set output "$work/projection.svg"
set datafile separator ","
set multiplot layout 1,2 title "Projection to order 8: max coefficient error against the number of samples"
set logscale xy
set format y "10^{%T}"
set xlabel "samples"
set grid
set key bottom left
set yrange [1e-16:10]
set title "a function of bands 0..7"
plot "$work/design.csv" using 2:3 with linespoints pt 7 title "t-designs", \
     "$work/gauss.csv" using 2:3 with linespoints pt 5 title "Gauss x equal phi", \
     "$work/grid.csv" using 2:3 with linespoints pt 9 title "equal-angle grid"
set yrange [1e-4:1]
set title "a 30-degree cap (not band-limited)"
plot "$work/design.csv" using 2:4 with linespoints pt 7 title "t-designs", \
     "$work/gauss.csv" using 2:4 with linespoints pt 5 title "Gauss x equal phi", \
     "$work/grid.csv" using 2:4 with linespoints pt 9 title "equal-angle grid"
unset multiplot
GP
gnuplot "$work/projection.gp"

kept=4,9,16,36,64,144,256,576,1024
"$zhf" needlets prt --quiet --scene sphere --transfer diffuse --kept $kept --csv "$work/prt_sphere.csv" >/dev/null
"$zhf" needlets prt --quiet --scene corner --transfer glossy --kept $kept --csv "$work/prt_corner.csv" >/dev/null
"$zhf" needlets prt --quiet --scene spheres --transfer diffuse --kept $kept --csv "$work/prt_spheres.csv" >/dev/null
for s in sphere corner spheres; do grep -v "^#" "$work/prt_$s.csv" | head -n -1 >"$work/prt_${s}_k.csv"; done
cat >"$work/prt.gp" <<GP
set terminal svg size 1200,420 font "sans,11" background "white"
set output "$work/prt_error.svg"
set datafile separator ","
set multiplot layout 1,3 title "Shading error (RMS, relative to the exact reference) against coefficients kept per vertex: SH bands, SH's largest, needlets' largest; bands 0..31, sun and sky"
set logscale xy
set format y "10^{%T}"
set xlabel "coefficients per vertex"
set grid
set key top right
GP
for s in "sphere diffuse" "corner glossy" "spheres diffuse"; do
  read -r scene transfer <<<"$s"
  cat >>"$work/prt.gp" <<GP
set title "$scene, $transfer"
plot "$work/prt_${scene}_k.csv" using 1:2 with linespoints lw 2 pt 7 lc rgb "#d62728" title "SH", \
     "" using 1:8 with linespoints lw 1.5 dt 3 pt 9 lc rgb "#ff7f0e" title "SH, K largest", \
     "" using 1:4 with linespoints lw 2 dt 2 pt 5 lc rgb "#1f77b4" title "needlets, K largest"
GP
done
echo "unset multiplot" >>"$work/prt.gp"
gnuplot "$work/prt.gp"
"$zhf" needlets prt --quiet --scene spheres --side 40 --kept 64 --shading-csv "$work/prt_images.csv" >/dev/null
grep -v "^#" "$work/prt_images.csv" >"$work/prt_images_data.csv"
cat >"$work/prt_images.gp" <<GP
set terminal svg size 1500,330 font "sans,11" background "white"
set output "$work/prt_images.svg"
set datafile separator ","
set multiplot layout 1,5 title "Three spheres over the ground, diffuse, sun and sky: shading (exact, then 64 coefficients a vertex) and the errors"
set size ratio -1
unset xtics
unset ytics
set palette grey
set cbrange [0:1.4]
set title "exact"
plot "$work/prt_images_data.csv" using 1:2:3 with image notitle
set title "SH, bands 0..7"
plot "" using 1:2:4 with image notitle
set title "needlets, largest 64"
plot "" using 1:2:5 with image notitle
set palette defined (-1 "#2166ac", 0 "white", 1 "#b2182b")
set cbrange [-0.12:0.12]
set title "SH - exact"
plot "" using 1:2:(\$4-\$3) with image notitle
set title "needlets - exact"
plot "" using 1:2:(\$5-\$3) with image notitle
unset multiplot
GP
gnuplot "$work/prt_images.gp"

for plot in needlet_kernels projection prt_error prt_images; do
  cp "$work/$plot.svg" "$root/docs/$plot.svg.tmp"
  mv "$root/docs/$plot.svg.tmp" "$root/docs/$plot.svg"
done
echo "wrote docs/needlet_kernels.svg, docs/projection.svg, docs/prt_error.svg and docs/prt_images.svg"
