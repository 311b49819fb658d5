#!/usr/bin/env bash
# The whole test suite: set up and build everything, then
#   1. every test on the Release build (ctest; the installed-package consumer test and the Python
#      module's pytest suite among them);
#   2. every test again under AddressSanitizer + UndefinedBehaviorSanitizer (the Python module
#      aside: an instrumented extension cannot load into an uninstrumented interpreter);
#   3. the runtime's, the generated kernels' and zhf::dispatch's tests cross-built for aarch64 and
#      run under qemu-aarch64 (scripts/test_aarch64.sh: correctness on ARM, never timing);
#   4. each libFuzzer target for ZHF_FUZZ_SECONDS (default 60) on its seed corpus, one per core at a time.
# Non-zero exit on any failure. ZHF_QUICK=1 runs stage 1 only.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
started=$SECONDS
elapsed() { echo "$(((SECONDS - started) / 60)) min $(((SECONDS - started) % 60)) s"; }
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS"

echo "== stage 1: tests (Release)"
ctest --test-dir "$ZHF_BUILD" --output-on-failure -j "$ZHF_JOBS"
echo "== stage 1 done at $(elapsed)"
[ "${ZHF_QUICK:-0}" = 1 ] && exit 0

echo "== stage 2: tests under ASan + UBSan"
asan_build="${ZHF_BUILD}-asan"
# -g1 (line tables, enough for symbolised reports): with -g, GCC's variable tracking over the
# generated order-8 kernels in bench/src/suite.cc ran out of memory on CI's machine. -O1 and no
# use-after-scope poisoning: GCC at -O2 poisoning every scoped temporary of the straight-line
# generated kernels (instantiated by the tests at every order, float and double) took 4.5x as long
# to compile them, and this stage's build twice as long (about 45 min against 23 on 2 cores). The
# readers keep use-after-scope checks in stage 4 (clang's default).
asan_flags="-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG -fno-sanitize-address-use-after-scope"
cmake -S "$ZHF_ROOT" -B "$asan_build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "$asan_flags" -DZHF_SANITIZE=ON -DZHF_BENCH=OFF -DZHF_PYTHON=OFF >/dev/null
cmake --build "$asan_build" -j "$ZHF_JOBS"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir "$asan_build" --output-on-failure -j "$ZHF_JOBS"
echo "== stage 2 done at $(elapsed)"

echo "== stage 3: aarch64 under qemu"
bash "$ZHF_ROOT/scripts/test_aarch64.sh"
echo "== stage 3 done at $(elapsed)"

echo "== stage 4: fuzzing"
fuzz_build="${ZHF_BUILD}-fuzz"
fuzz_flags="-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG"
CC=clang CXX=clang++ cmake -S "$ZHF_ROOT" -B "$fuzz_build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "$fuzz_flags" -DZHF_FUZZ=ON >/dev/null
cmake --build "$fuzz_build" -j "$ZHF_JOBS"
# One fuzzer per core at a time: each for ZHF_FUZZ_SECONDS on a private copy of its corpus.
fuzz_one() {
  local corpus=$1 target="fuzz_$1" work
  work=$(mktemp -d)
  cp "$ZHF_ROOT"/tests/fuzz_corpus/$corpus/* "$work/"
  "$fuzz_build/fuzz/$target" -max_total_time="${ZHF_FUZZ_SECONDS:-60}" -dict="$ZHF_ROOT/tests/fuzz_corpus/json.dict" \
    -max_len=200000 -artifact_prefix="$work/" -print_final_stats=1 "$work" >"$work/log" 2>&1 || true
  echo "-- $target: $(grep -E '^stat::number_of_executed_units' "$work/log" | tr -s ' ' | cut -d' ' -f2) runs"
  grep -E "ERROR|SUMMARY" "$work/log" || true
  if ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* >/dev/null 2>&1; then
    echo "$target found a failing input: $(ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* 2>/dev/null | head -1)" >&2
    return 1
  fi
  rm -rf "$work"
}
pids=()
failed=0
for corpus in json lobe_table coefficients scene manifest rotation_text ply hdr splat_formats healpix_fits; do
  fuzz_one "$corpus" &
  pids+=($!)
  if [ ${#pids[@]} -ge "$ZHF_JOBS" ]; then
    wait "${pids[0]}" || failed=1
    pids=("${pids[@]:1}")
  fi
done
for pid in "${pids[@]}"; do wait "$pid" || failed=1; done
[ "$failed" = 0 ] || exit 1
echo "== stage 4 done at $(elapsed)"
echo "all stages passed"
