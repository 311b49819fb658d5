#!/usr/bin/env bash
# Rewrites tests/data/uniform.sog: splat-transform's SOG (-g cpu) of the uniform scene
# crosscheck/uniform_sog.py describes, and uniform_deflated.sog, the same entries deflated by
# Python's zipfile (splat-transform stores them). tests/splat/sog_test.cc reads both.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/setup.sh"
cd "$ZHF_ROOT"
source crosscheck/splat_transform.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 crosscheck/uniform_sog.py "$work/uniform.ply"
"$st" -q -g cpu "$work/uniform.ply" "$work/uniform.sog"
mv "$work/uniform.sog" tests/data/uniform.sog
/usr/bin/python3 crosscheck/uniform_sog.py --deflate tests/data/uniform.sog tests/data/uniform_deflated.sog
