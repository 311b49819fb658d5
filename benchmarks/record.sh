#!/usr/bin/env bash
# Runs one benchmark command and writes its output to a results file, after a header that says
# what ran where: the command, compiler, CPU and its vector extensions, cores, commit (and whether
# the tree was clean) and date. Pinned to core 1 where the machine has two or more, unless
# RECORD_ALL_CORES=1. The file is written through a temporary beside it, so an interrupted run
# leaves the previous one.
#   bash benchmarks/record.sh OUT "what the build is" COMMAND [ARGS...]
set -euo pipefail
[ $# -ge 3 ] || { echo "usage: benchmarks/record.sh OUT BUILD COMMAND [ARGS...]" >&2; exit 2; }
out=$1 build=$2
shift 2
cd "$(dirname "${BASH_SOURCE[0]}")/.."
pin=()
[ "${RECORD_ALL_CORES:-0}" != 1 ] && [ "$(nproc)" -ge 2 ] && command -v taskset > /dev/null && pin=(taskset -c 1)
cpu=$(grep -m1 "model name" /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')
isa=$(grep -q -w avx512f /proc/cpuinfo && echo "AVX2, AVX-512" || { grep -q -w avx2 /proc/cpuinfo && echo "AVX2, no AVX-512" || echo "no AVX2"; })
# The outputs of a run (results, the plots drawn from them) do not count: a second run rewrites
# the first's files before it records the next one.
tree=$(git diff --quiet HEAD -- . ':(exclude)benchmarks/results' ':(exclude)docs/*.svg' && echo "clean tree" || echo "modified tree")
tmp=$(mktemp "$out.XXXXXX")
trap 'rm -f "$tmp"' EXIT
{
  shown="${pin[*]}${pin[*]:+ }$*"
  echo "# ${shown//$PWD\//}; $build"
  echo "# $(g++ --version | head -1); CPU: $cpu ($isa), $(nproc) cores; commit $(git rev-parse --short HEAD) ($tree); $(date -u +%F)"
  "${pin[@]}" "$@"
} > "$tmp"
chmod a+r "$tmp"
mv "$tmp" "$out"
trap - EXIT
cat "$out"
