#!/usr/bin/env bash
# The whole test suite: set up and build everything, then
#   1. every test on the Release build (ctest; the installed-package consumer test and the Python
#      module's pytest suite among them);
#   2. every test again under AddressSanitizer + UndefinedBehaviorSanitizer (the Python module
#      aside: an instrumented extension cannot load into an uninstrumented interpreter);
#   3. each libFuzzer target for ZHF_FUZZ_SECONDS (default 60) on its seed corpus.
# Non-zero exit on any failure. ZHF_QUICK=1 runs stage 1 only.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS"

echo "== stage 1: tests (Release)"
ctest --test-dir "$ZHF_BUILD" --output-on-failure -j "$ZHF_JOBS"
[ "${ZHF_QUICK:-0}" = 1 ] && exit 0

echo "== stage 2: tests under ASan + UBSan"
asan_build="${ZHF_BUILD}-asan"
# -g1 (line tables, enough for symbolised reports): with -g, GCC's variable tracking over the
# generated order-8 kernels in bench/src/suite.cc ran out of memory on CI's machine.
debug_flags="-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG"
cmake -S "$ZHF_ROOT" -B "$asan_build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "$debug_flags" -DZHF_SANITIZE=ON -DZHF_BENCH=OFF -DZHF_PYTHON=OFF >/dev/null
cmake --build "$asan_build" -j "$ZHF_JOBS"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir "$asan_build" --output-on-failure -j "$ZHF_JOBS"

echo "== stage 3: fuzzing"
fuzz_build="${ZHF_BUILD}-fuzz"
CC=clang CXX=clang++ cmake -S "$ZHF_ROOT" -B "$fuzz_build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "$debug_flags" -DZHF_FUZZ=ON >/dev/null
cmake --build "$fuzz_build" -j "$ZHF_JOBS"
for corpus in json lobe_table coefficients scene manifest rotation_text ply hdr; do
  target="fuzz_$corpus"
  work=$(mktemp -d)
  cp "$ZHF_ROOT"/tests/fuzz_corpus/$corpus/* "$work/"
  echo "-- $target for ${ZHF_FUZZ_SECONDS:-60} s"
  "$fuzz_build/fuzz/$target" -max_total_time="${ZHF_FUZZ_SECONDS:-60}" -dict="$ZHF_ROOT/tests/fuzz_corpus/json.dict" \
    -max_len=200000 -artifact_prefix="$work/" -print_final_stats=1 "$work" 2>&1 \
    | grep -E "^(Done|stat::number_of_executed_units)|ERROR|SUMMARY" || true
  if ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* >/dev/null 2>&1; then
    echo "$target found a failing input: $(ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* 2>/dev/null | head -1)" >&2
    exit 1
  fi
  rm -rf "$work"
done
echo "all stages passed"
