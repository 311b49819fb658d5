#!/usr/bin/env bash
# The runtime, the generated kernels and zhf::dispatch (its NEON path) cross-built for aarch64
# with Debian's g++-aarch64-linux-gnu, and their tests run under qemu-aarch64: correctness on ARM
# only, an emulator's timings mean nothing. Run by test.sh; on its own after setup.sh's packages.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cross_build="${ZHF_BUILD}-aarch64"
cmake -S "$ZHF_ROOT" -B "$cross_build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DZHF_WERROR=ON -DZHF_RUNTIME_TESTS_ONLY=ON \
  -DCMAKE_TOOLCHAIN_FILE="$ZHF_ROOT/cmake/aarch64-linux-gnu.cmake" >/dev/null
cmake --build "$cross_build" -j "$ZHF_JOBS"
ctest --test-dir "$cross_build" --output-on-failure -j "$ZHF_JOBS"
