#!/usr/bin/env bash
# The whole test suite: set up, build, run every test; non-zero exit on any failure.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
ctest --test-dir "$ZHF_BUILD" --output-on-failure -j "$ZHF_JOBS"
