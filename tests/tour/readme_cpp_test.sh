#!/usr/bin/env bash
# The README tour's C++ snippets as a user pastes them: each ```cpp block of "A five-minute tour"
# is compiled (syntax and templates, no object code) with its #include lines on top and its
# statements in a function whose parameters are the arrays and counts the snippet names. A block
# that includes the header-only runtime must reach the generated kernels of the orders it uses
# only: the headers the compiler opens (-H) may hold no other zhf_orderN.h, and not zhf_kernels.h.
# Usage: readme_cpp_test.sh SOURCE_DIR [CXX]
set -euo pipefail
source_dir=$1
cxx=${2:-c++}
scratch=$(mktemp -d "${TMPDIR:-/tmp}/zhf-readme-cpp-XXXXXX")
trap 'rm -rf "$scratch"' EXIT
awk -v dir="$scratch" '/^## A five-minute tour/ {tour = 1; next} /^## / {tour = 0}
     tour && /^```cpp$/ {block++; inside = 1; file = dir "/block" block ".txt"; next}
     inside && /^```$/ {close(file); inside = 0; next}
     inside {print > file}' "$source_dir/README.md"
blocks=("$scratch"/block*.txt)
[ -e "${blocks[0]}" ] || { echo "FAIL: no cpp blocks found in the README tour"; exit 1; }
status=0
for block in "${blocks[@]}"; do
  name=$(basename "$block" .txt)
  {
    echo "#include <cstddef>"
    grep '^#include' "$block"
    echo "void example(std::size_t count, const float* R, const float* in, float* out, float* splats,"
    echo "             const float* Rs, const float* ins, float* outs, const zhf::runtime::LobeTable* table_pointer) {"
    grep -q '\btable\b' "$block" && echo "  const zhf::runtime::LobeTable& table = *table_pointer;"
    echo "  (void)count, (void)R, (void)in, (void)out, (void)splats, (void)Rs, (void)ins, (void)outs, (void)table_pointer;"
    grep -v '^#include' "$block"
    echo "}"
  } >"$scratch/$name.cc"
  # LobeTable is declared for every block: the dispatch block names no runtime header of its own.
  sed -i '1a #include "zhf/runtime/lobe_table.h"' "$scratch/$name.cc"
  if ! "$cxx" -std=c++17 -march=x86-64-v3 -fsyntax-only -H -I "$source_dir/runtime/include" -I "$source_dir/generated/cpp" \
      -I "$source_dir/dispatch/include" "$scratch/$name.cc" 2>"$scratch/$name.log"; then
    grep -v '^\.' "$scratch/$name.log" | head -20
    echo "FAIL: README cpp $name does not compile"
    status=1
    continue
  fi
  if grep -q 'zhf/runtime/rotator.h' "$block"; then
    used=$(grep -o 'zhf_order[0-9]*\.h' "$block" | sort -u | tr '\n' ' ' || true)
    opened=$(grep -o 'zhf_order[0-9]*\.h\|zhf_kernels\.h' "$scratch/$name.log" | sort -u | tr '\n' ' ' || true)
    if [ "$opened" != "$used" ]; then
      echo "FAIL: README cpp $name includes $used but the compiler opened $opened"
      status=1
      continue
    fi
    echo "ok   README cpp $name: compiles, opens only $opened"
  else
    echo "ok   README cpp $name: compiles"
  fi
done
exit $status
