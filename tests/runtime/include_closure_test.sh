#!/usr/bin/env bash
# The runtime's rotation headers stand alone: a program that rotates includes the standard library
# and zhf/runtime headers only, and none of the readers (JSON, files, table I/O). Lists every
# header the preprocessor opens (-H) for a translation unit that includes only the header named.
# Usage: include_closure_test.sh CXX RUNTIME_INCLUDE_DIR
set -euo pipefail
cxx=$1
include=$2
status=0
for header in rotator.h dense_rotation.h lobe_table.h table_rotation.h zxzxz_rotation.h band_rows.h soa_batch.h lanes.h product.h; do
  opened=$(echo "#include \"zhf/runtime/$header\"" | "$cxx" -std=c++17 -fsyntax-only -H -I "$include" -x c++ - 2>&1 >/dev/null |
    sed -n 's/^\.\+ //p' | sort -u)
  own=$(echo "$opened" | grep "$include/" || true)
  if [ -z "$own" ]; then
    echo "FAIL $header: the preprocessor opened no zhf header (did it compile?)"
    status=1
    continue
  fi
  readers=$(echo "$own" | grep -E '/(json|read_file|table_io)\.h$' || true)
  others=$(echo "$opened" | grep -v "$include/" | grep -vE '^/usr/(include|lib)/' || true)
  if [ -n "$readers" ] || [ -n "$others" ]; then
    echo "FAIL $header pulls in:" $readers $others
    status=1
  else
    echo "ok   $header: $(echo "$own" | wc -l) zhf headers, no reader"
  fi
done
exit $status
