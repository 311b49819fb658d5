#!/usr/bin/env bash
# Sourced by the benchmarks that set the default build against an x86-64-v3 one: sets up, builds
# TARGET in the Release build (no -march, as users get zhf) and in build-x86-64-v3/ (configured
# -DCMAKE_CXX_FLAGS=-march=x86-64-v3), and leaves ZHF_ROOT, ZHF_BUILD and ZHF_BUILD_V3 set.
#   source benchmarks/both_builds.sh TARGET
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
ZHF_BUILD_V3=$ZHF_ROOT/build-x86-64-v3
cmake -S "$ZHF_ROOT" -B "$ZHF_BUILD_V3" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-march=x86-64-v3 > /dev/null
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target "$1"
cmake --build "$ZHF_BUILD_V3" -j "$ZHF_JOBS" --target "$1"
cd "$ZHF_ROOT"
