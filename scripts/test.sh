#!/usr/bin/env bash
# The whole test suite: set up and build everything, then the three sets of tests/CMakeLists.txt:
#   1. the release set on the Release build (ctest; the installed-package consumer test and the
#      Python module's pytest suite among them);
#   2. one clang build under AddressSanitizer + UndefinedBehaviorSanitizer: the sanitized set, the
#      runtime's memory paths, the generated kernels and the readers' libraries (those that run the
#      CLI run the Release build's), then each libFuzzer target for
#      ZHF_FUZZ_SECONDS (default 10: a smoke run; longer runs by hand) on its seed corpus with its dictionary, one per core at a time;
#      a fuzzer that finds a failing input, fails to start or runs no input fails the stage;
#   3. the aarch64 set (the generated kernels, the batch paths, every method, zhf::dispatch)
#      cross-built and run under qemu-aarch64 (scripts/test_aarch64.sh: correctness on ARM, never timing).
# Non-zero exit on any failure. ZHF_QUICK=1 runs stage 1 only.
set -euo pipefail
# The web parts' tools first, so that the build configured next finds emscripten.
bash "$(dirname "${BASH_SOURCE[0]}")/setup_web.sh"
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
# Their tests fail where the browser is missing, instead of skipping.
export ZHF_REQUIRE_BROWSER=1
started=$SECONDS
elapsed() { echo "$(((SECONDS - started) / 60)) min $(((SECONDS - started) % 60)) s"; }
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS"

# Lavapipe (the Vulkan driver without a GPU) compiles each shader with LLVM on first use and
# caches it in the home directory, which a clean machine (CI) does not have: the tests take its
# quicker compiles, without LLVM's optimisation passes and at 128-bit vectors (the checked-in
# GLSL kernels of orders 2..8, cold: 66 s, 14 s so, 5 s cached; stage 1's ctest, cold: 262 -> 159 s). The
# results are still the driver's, held to the same tolerances. (Exported here, not in each test's
# ENVIRONMENT: gtest_discover_tests keeps only the first item of a list there.)
export GALLIVM_PERF=${GALLIVM_PERF:-nopt} LP_NATIVE_VECTOR_WIDTH=${LP_NATIVE_VECTOR_WIDTH:-128}

echo "== stage 1: tests (Release)"
ctest --test-dir "$ZHF_BUILD" --output-on-failure -j "$ZHF_JOBS"
echo "== stage 1 done at $(elapsed)"
[ "${ZHF_QUICK:-0}" = 1 ] && exit 0

echo "== stage 2: sanitized tests and fuzzing (clang, ASan + UBSan)"
fuzz_build="${ZHF_BUILD}-fuzz"
fuzz_flags="-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG"
# zhf::dispatch's baseline units as stage 1 compiled them (dispatch/CMakeLists.txt).
CC=clang CXX=clang++ cmake -S "$ZHF_ROOT" -B "$fuzz_build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "$fuzz_flags" -DZHF_FUZZ=ON \
  -DZHF_DISPATCH_BASELINE_ARCHIVE="$ZHF_BUILD/dispatch/libzhf_dispatch_baseline.a" >/dev/null
cmake --build "$fuzz_build" -j "$ZHF_JOBS"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ZHF_TEST_BINARY="$ZHF_BUILD/cli/zhf" ctest --test-dir "$fuzz_build" --output-on-failure -j "$ZHF_JOBS"
echo "== sanitized tests done at $(elapsed)"
# One fuzzer per core at a time: each for ZHF_FUZZ_SECONDS on a private copy of its corpus.
fuzz_one() {
  local corpus=$1 dict=$2 target="fuzz_$1" work status=0 runs
  work=$(mktemp -d)
  cp "$ZHF_ROOT"/tests/fuzz_corpus/$corpus/* "$work/"
  "$fuzz_build/fuzz/$target" -max_total_time="${ZHF_FUZZ_SECONDS:-10}" -dict="$ZHF_ROOT/tests/fuzz_corpus/$dict.dict" \
    -max_len=200000 -artifact_prefix="$work/" -print_final_stats=1 "$work" >"$work/log" 2>&1 || status=$?
  runs=$(grep -E '^stat::number_of_executed_units' "$work/log" | tr -s ' ' | cut -d' ' -f2 || true)
  echo "-- $target: ${runs:-no} runs, exit status $status"
  grep -E "ERROR|SUMMARY" "$work/log" || true
  if ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* >/dev/null 2>&1; then
    echo "$target found a failing input: $(ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* 2>/dev/null | head -1)" >&2
    return 1
  fi
  if [ "$status" != 0 ] || [ -z "$runs" ] || [ "$runs" = 0 ]; then
    echo "$target did not run (exit status $status, ${runs:-no} inputs run); its log:" >&2
    tail -n 20 "$work/log" >&2
    rm -rf "$work"
    return 1
  fi
  rm -rf "$work"
}
pids=()
failed=0
for fuzzer in json:json lobe_table:json coefficients:json scene:json manifest:json rotation_text:rotation_text ply:ply \
              hdr:hdr splat_formats:splat_formats healpix_fits:healpix_fits; do
  fuzz_one "${fuzzer%%:*}" "${fuzzer##*:}" &
  pids+=($!)
  if [ ${#pids[@]} -ge "$ZHF_JOBS" ]; then
    wait "${pids[0]}" || failed=1
    pids=("${pids[@]:1}")
  fi
done
for pid in "${pids[@]}"; do wait "$pid" || failed=1; done
[ "$failed" = 0 ] || exit 1
echo "== stage 2 done at $(elapsed)"

echo "== stage 3: aarch64 under qemu"
bash "$ZHF_ROOT/scripts/test_aarch64.sh"
echo "== stage 3 done at $(elapsed)"
echo "all stages passed"
