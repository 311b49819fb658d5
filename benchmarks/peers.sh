#!/usr/bin/env bash
# zhf against its peers as users get it: the peer harness (../shared/peers, or $PEERS) built twice
# and run back to back on this machine, pinned to one core:
#   default build   everything -O3 without -march; zhf's row is zhf::dispatch (the project's Release
#                   libzhf_dispatch.a, its path picked at run time) through zhf_dispatch_adapter.cc.txt;
#   x86-64-v3 build everything -O3 -march=x86-64-v3; zhf's rows header-only, through
#                   zhf_kernels_adapter.cc.txt and zhf_table_adapter.cc.txt.
# The harness is copied to a private scratch folder and its adapters replaced there (its own copy
# is never changed). Writes, through benchmarks/record.sh, peers_default_build.txt and
# peers_x86_64_v3.txt (orders 2..8, 16, 32, 64), then peers_default_build_order128.txt and
# peers_x86_64_v3_order128.txt (K = 4, 3 repetitions: google's rotation takes 0.1 s there) into
# RESULTS (benchmarks/performance.sh sets it; benchmarks/performance_tables.py makes the tables).
# Environment: PEERS, RESULTS (required), REPS (7), K (1024).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cd "$ZHF_ROOT"
orders=2,3,4,5,6,7,8,16,32,64
peers=${PEERS:-$ZHF_ROOT/../shared/peers}
results=${RESULTS:?peers.sh: set RESULTS (benchmarks/performance.sh runs it)}
reps=${REPS:-7}
k=${K:-1024}
[ -f "$peers/build.sh" ] && [ -f "$peers/run.sh" ] || { echo "peers.sh: no peer harness at $peers (set PEERS)" >&2; exit 1; }
mkdir -p "$results"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target zhf_dispatch

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# copy NAME: the harness in $scratch/NAME/harness, to be built into $scratch/NAME/out.
copy() {
  mkdir -p "$scratch/$1"
  cp -r "$peers" "$scratch/$1/harness"
}

# The default build: the dispatch adapter in place of the table adapter, compiled against the
# library's header and linked with it (two edits to the copy's build.sh, each checked).
copy default
cp benchmarks/peers/zhf_dispatch_adapter.cc.txt "$scratch/default/harness/src/m_zhf_table.cc"
build="$scratch/default/harness/build.sh"
table_rule='rule zhf_table.o "$S/m_zhf_table.cc" '"'"'$(NATIVE)'"'"' "$ZHF_INC"'
link_rule='-lhealpix_cxx -pthread'
grep -qF "$table_rule" "$build" && grep -qF "$link_rule" "$build" ||
  { echo "peers.sh: $peers/build.sh has changed; update the two edits in benchmarks/peers.sh" >&2; exit 1; }
library="$ZHF_BUILD/dispatch/libzhf_dispatch.a"
sed -i -e "s|$(printf '%s' "$table_rule" | sed 's/[][\.*^$|]/\\&/g')|& \"-I$ZHF_ROOT/dispatch/include\"|" \
  -e "s|$link_rule|$library &|" "$build"
grep -qF "$library" "$build" && grep -qF -- "-I$ZHF_ROOT/dispatch/include" "$build" ||
  { echo "peers.sh: could not edit the copy of build.sh" >&2; exit 1; }

copy v3
cp benchmarks/peers/zhf_table_adapter.cc.txt "$scratch/v3/harness/src/m_zhf_table.cc"
cp benchmarks/peers/zhf_kernels_adapter.cc.txt "$scratch/v3/harness/src/m_zhf.cc"

export ZHF_SRC=$ZHF_ROOT
OUT="$scratch/default/out" NATIVE_FLAGS="-O3 -std=c++17 -DNDEBUG" bash "$scratch/default/harness/build.sh"
OUT="$scratch/v3/out" NATIVE_FLAGS="-O3 -march=x86-64-v3 -std=c++17 -DNDEBUG" bash "$scratch/v3/harness/build.sh"

# run NAME FILE WHAT ORDERS K REPS: one run of the NAME build into $results/FILE.
run() {
  bash benchmarks/record.sh "$results/$2" "$3" env OUT="$scratch/$1/out" bash "$scratch/$1/harness/run.sh" \
    --orders "$4" --K "$5" --reps "$6" > /dev/null || { echo "peers.sh: the $1 run failed" >&2; exit 1; }
}
default="peers and zhf -O3 (no -march); zhf through zhf::dispatch"
v3="peers and zhf -O3 -march=x86-64-v3; zhf header-only"
run default peers_default_build.txt "$default" "$orders" "$k" "$reps"
run v3 peers_x86_64_v3.txt "$v3" "$orders" "$k" "$reps"
run default peers_default_build_order128.txt "$default" 128 4 3
run v3 peers_x86_64_v3_order128.txt "$v3" 128 4 3
