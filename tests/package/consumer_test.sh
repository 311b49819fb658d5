#!/usr/bin/env bash
# The installed package as a user meets it: `cmake --install` into a private prefix, then
#   1. a separate project finds it with find_package(zhf CONFIG), builds and runs (rotates and checks);
#   2. the same source built with pkg-config's flags only;
#   3. the installed zhf, run from elsewhere, rotates, and generates from the installed lobe tables:
#      a table damaged in the prefix is the one named in its error, and a moved prefix still works.
# Usage: consumer_test.sh BUILD_DIR
set -euo pipefail
build=$1
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/zhf-package-XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
fail() { echo "package test: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" >/dev/null
# A package built under the sanitizers holds an instrumented zhf::dispatch: its consumers link
# the sanitizers' runtimes too.
sanitize=""
if grep -qs '^ZHF_SANITIZE:BOOL=ON' "$build/CMakeCache.txt"; then sanitize="-fsanitize=address,undefined"; fi
table=$prefix/share/zhf/generated/lobes/order_12.json
[ -f "$table" ] || fail "no installed lobe table at $table"

echo "-- find_package(zhf CONFIG)"
env -u CXXFLAGS -u LDFLAGS cmake -S "$here/consumer" -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_FLAGS="$sanitize" -DCMAKE_EXE_LINKER_FLAGS="$sanitize" >/dev/null
cmake --build "$work/consumer" >/dev/null
"$work/consumer/consumer" "$table"

echo "-- pkg-config zhf"
flags=$(PKG_CONFIG_PATH="$prefix/share/pkgconfig" pkg-config --cflags --libs zhf)
# shellcheck disable=SC2086  # the flags are words
g++ -std=c++17 -O2 $sanitize "$here/consumer/main.cc" $flags -o "$work/consumer_pc"
"$work/consumer_pc" "$table"

echo "-- the installed zhf rotates, and finds its installed tables"
cd "$work"
python3 -c "print(' '.join('0.01' for _ in range(144)))" > coefficients.txt
"$prefix/bin/zhf" rotate --coeffs coefficients.txt --axis-angle "0 0 1 0.5" --out turned.json
[ -s turned.json ] || fail "zhf rotate wrote nothing"
mkdir first damaged moved
(cd first && "$prefix/bin/zhf" generate --out gen > /dev/null)
[ -s first/gen/manifest.json ] || fail "zhf generate wrote no manifest"
lobes=$prefix/share/zhf/generated/lobes/order_8.json
cp "$lobes" saved.json
echo '{"format": "zhf-lobes-1", "order": 3}' > "$lobes"
if (cd damaged && "$prefix/bin/zhf" generate --out gen > /dev/null 2> ../error.txt); then
  fail "zhf generate accepted a damaged installed table"
fi
grep -qF "$lobes" error.txt || fail "the error does not name the installed table: $(cat error.txt)"
cp saved.json "$lobes"
mv "$prefix" "$work/prefix_moved"
(cd moved && "$work/prefix_moved/bin/zhf" generate --out gen > /dev/null)
diff -r first/gen moved/gen > /dev/null || fail "the moved prefix generates differently"
echo "package test passed"
