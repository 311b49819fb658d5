#!/usr/bin/env bash
# The Python module as users get it (the Release build, no -march) against one built with
# -DCMAKE_CXX_FLAGS=-march=x86-64-v3 (in build-x86-64-v3/): bench/python_builds_bench.py into
# bench/results/python_builds.txt, then again with the builds' places swapped into
# python_builds_swapped.txt, through bench/record.sh; docs/performance.md quotes them. Arguments
# go to the bench (default --reps 15).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/both_builds.sh" _zhf
[ $# -gt 0 ] || set -- --reps 15
default=${ZHF_BUILD#$ZHF_ROOT/}/python v3=${ZHF_BUILD_V3#$ZHF_ROOT/}/python
bench() { bash bench/record.sh "$1" "Release -O3 -DNDEBUG: no -march against -march=x86-64-v3" /usr/bin/python3 bench/python_builds_bench.py "${@:2}"; }
bench bench/results/python_builds.txt "$default" "$v3" "$@"
bench bench/results/python_builds_swapped.txt "$v3" "$default" "$@"
