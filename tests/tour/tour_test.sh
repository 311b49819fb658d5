#!/usr/bin/env bash
# The README tour as a newcomer runs it: every ```sh block of "A five-minute tour", in order, in
# one shell, at the top of a checkout whose build/ scripts/main.sh made. It runs in a scratch
# folder that links the checkout's folders (so tour/ lands there, not in the checkout), and checks
# that every file the tour names under tour/ exists afterwards.
# Usage: tour_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir=$1
build_dir=$2
scratch=$(mktemp -d "${TMPDIR:-/tmp}/zhf-tour-XXXXXX")
trap 'rm -rf "$scratch"' EXIT
for folder in examples generated runtime bench scripts; do ln -s "$source_dir/$folder" "$scratch/$folder"; done
ln -s "$build_dir" "$scratch/build"
# The blocks, in order: the lines between ```sh and ``` inside the tour section.
awk '/^## A five-minute tour/ {tour = 1; next} /^## / {tour = 0} tour && /^```sh$/ {block = 1; next}
     block && /^```$/ {block = 0; print ""; next} block {print}' "$source_dir/README.md" >"$scratch/tour.sh"
[ -s "$scratch/tour.sh" ] || { echo "FAIL: no sh blocks found in the README tour"; exit 1; }
cd "$scratch"
echo "== running $(grep -c . tour.sh) lines of the README tour"
if ! bash -euo pipefail tour.sh >tour.log 2>&1; then
  tail -20 tour.log
  echo "FAIL: the tour stopped (log above)"
  exit 1
fi
# Every tour/ path the blocks name was made.
status=0
for path in $(grep -o 'tour/[A-Za-z0-9_./-]*' tour.sh | sort -u); do
  if [ -e "$path" ]; then echo "ok   $path"; else echo "FAIL $path was not made"; status=1; fi
done
[ -e tour/shaders/zhf_order4.glsl ] || { echo "FAIL tour/shaders/zhf_order4.glsl was not made"; status=1; }
grep -q "verify: pass" tour.log || { echo "FAIL zhf verify did not pass"; status=1; }
grep -q "normalisation\|not a unit" tour.log && { echo "FAIL a tour input drew a warning"; status=1; }
exit $status
