#!/usr/bin/env bash
# The main job on built-in defaults: install the packages it needs (only those), build the zhf
# binary (only it), emit every kernel (orders 2..8; C++, HLSL, GLSL, WGSL) from the checked-in
# lobe tables into a scratch directory, print the summary, then compile and run all of them against
# the double reference (the shaders on Vulkan; lavapipe when there is no GPU).
set -euo pipefail
ZHF_SETUP=main source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf
cd "$ZHF_ROOT"
scratch=${ZHF_SCRATCH:-$(mktemp -d "${TMPDIR:-/tmp}/zhf-main-XXXXXX")}
echo "== zhf generate --out $scratch"
"$ZHF_BUILD/cli/zhf" generate --out "$scratch"
echo
echo "== zhf verify --generated $scratch"
"$ZHF_BUILD/cli/zhf" verify --generated "$scratch"
