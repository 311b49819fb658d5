#!/usr/bin/env bash
# The user's workflow from their own lobe tables: optimize orders 3..8 with another seed into a
# folder (a short search: the workflow is under test, not the search), generate a whole tree from
# that folder, and verify every function of it against the double reference. The tree must name
# the user's tables in its kernels, have no lanes tables (the folder has none), pass, and its
# headers compile for every instruction set's path choice.
# Usage: own_tables_test.sh ZHF_BINARY SOURCE_DIR CXX
set -euo pipefail
zhf=$1 source=$2 cxx=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/zhf-own-tables-XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir "$work/tables"
for order in 3 4 5 6 7 8; do
  "$zhf" optimize --order "$order" --seed 7 --population 16 --generations 4 --stall 2 --local-search-stall 0 \
    --threads 1 --quiet --out "$work/tables/order_$order.json" >/dev/null
done
"$zhf" generate --tables "$work/tables" --out "$work/tree"
grep -q "made by: zhf optimize --order 8 --seed 7" "$work/tree/cpp/zhf_order8.h" ||
  { echo "FAIL: the order-8 kernels do not name the user's table" >&2; exit 1; }
if ls "$work/tree/cpp/" | grep -q lanes; then
  echo "FAIL: lanes tables in a tree made from a folder without them" >&2; exit 1
fi
if grep -q "Path::kLanes;" "$work/tree/cpp/zhf_paths.h"; then
  echo "FAIL: zhf_paths.h picks lanes kernels the tree does not have" >&2; exit 1
fi
"$zhf" verify --generated "$work/tree" --orders 2..8 --langs cpp,glsl --rotations 100 --quiet
# The path header follows the tree: every order's fastest rotator compiles and rotates, on the
# baseline and on the AVX2 build (whose measured table names lanes kernels this tree lacks).
cat >"$work/use.cc" <<'EOF'
#include <vector>
#include "zhf_kernels.h"
int main() {
  const float R[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
  for (int order = 2; order <= 8; ++order) {
    const auto rotator = zhf::gen::fastest_rotator<float>(order);
    std::vector<float> in(order * order, 1.0f), out(order * order);
    rotator.rotate(R, in.data(), out.data());
    if (out[0] != 1.0f) return 1;
  }
  return 0;
}
EOF
for flags in "" "-march=x86-64-v3"; do
  if [ -n "$flags" ] && ! grep -qw avx2 /proc/cpuinfo; then continue; fi
  "$cxx" -std=c++17 -O1 $flags -I "$source/runtime/include" -I "$work/tree/cpp" "$work/use.cc" -o "$work/use"
  "$work/use" || { echo "FAIL: the tree's fastest rotators (${flags:-baseline})" >&2; exit 1; }
done
echo "own tables: optimize, generate, verify and the path header pass"
