#!/usr/bin/env bash
# Installs what the Python module needs (as root), builds it and installs the zhf package into
# Debian Python's user site
# (python3 -m site --user-site), or into the folder given as the first argument. A zhf package
# already there is replaced only if zhf wrote it (its py.typed and _zhf module are there);
# anything else of that name is left alone and the install refused.
set -euo pipefail
ZHF_SETUP=python source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cmake --build "$ZHF_BUILD" -j "$ZHF_JOBS" --target _zhf
python=/usr/bin/python3
site=${1:-$("$python" -m site --user-site)}
built="$ZHF_BUILD/python/zhf"
target="$site/zhf"
if [ -e "$target" ] && ! { [ -f "$target/py.typed" ] && ls "$target"/_zhf*.so >/dev/null 2>&1; }; then
  echo "zhf install: $target exists and is not a zhf package this script installed; remove it yourself" >&2
  exit 1
fi
mkdir -p "$site"
staging=$(mktemp -d "$site/.zhf-install-XXXXXX")
trap 'rm -rf "$staging"' EXIT
cp -R "$built" "$staging/zhf"
find "$staging" -name __pycache__ -prune -exec rm -rf {} +
if [ -e "$target" ]; then
  mv "$target" "$staging/previous"
fi
mv "$staging/zhf" "$target"
echo "zhf $("$python" -c 'import sys; sys.path.insert(0, sys.argv[1]); import zhf; print(zhf.__version__)' "$site") installed in $target"
