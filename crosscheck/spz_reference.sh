#!/usr/bin/env bash
# Rewrites tests/data/spz_reference/ (crosscheck/spz_reference.cc): the reference .spz library's
# files for every coordinate-system record and its readings of them. Argument: a checkout of
# https://github.com/nianticlabs/spz (the files in the project came from commit
# 21715c3b7a609ea6fb7c69b8ae42181a12b59f22), built here with its extensions, zlib and zstd.
set -euo pipefail
spz=$(cd "$1" && pwd)
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -std=c++17 -O1 -DSPZ_BUILD_EXTENSIONS -I"$spz/src/cc" -I"$spz/extensions/cc" -I"$root/sh/include" "$root/crosscheck/spz_reference.cc" \
  "$spz"/src/cc/*.cc "$spz"/extensions/cc/*.cc -lz -lzstd -o "$work/spz_reference"
mkdir -p "$work/out"
"$work/spz_reference" "$work/out" > /dev/null
rm -rf "$root/tests/data/spz_reference"
mv "$work/out" "$root/tests/data/spz_reference"
