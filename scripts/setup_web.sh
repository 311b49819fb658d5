#!/usr/bin/env bash
# What zhf's web parts need besides setup.sh's (sourced by test.sh and the web benchmark; safe to
# run again, it only does what is missing): Debian's emscripten (the WebAssembly module; its
# optimizer runs on node-acorn) and chromium (the WGSL kernels and the page run in its WebGPU,
# headless, on SwiftShader), and from npm, pinned, into the checkout's tools/node: puppeteer-core
# (drives that chromium), TypeScript and @webgpu/types (the package's declarations are
# type-checked), fzstd (the example page's .spz version 4 reader). Never installed globally.
set -euo pipefail
ZHF_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

web_packages=(emscripten node-acorn chromium nodejs npm)
missing=()
for p in "${web_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# A node that came from elsewhere (nodesource) counts.
if command -v node >/dev/null && command -v npm >/dev/null; then
  missing=("${missing[@]/nodejs/}")
  missing=("${missing[@]/npm/}")
fi
read -r -a missing <<<"${missing[*]}"
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -eq 0 ]; then
    echo "zhf setup_web: installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  else
    echo "zhf setup_web: missing Debian packages: ${missing[*]} (run as root, or: sudo apt-get install ${missing[*]})" >&2
    exit 1
  fi
fi

# The npm tools, pinned; naga-wasm is setup.sh's (zhf verify's second WGSL compiler).
tools=(puppeteer-core@24.43.1 typescript@5.9.3 @webgpu/types@0.1.74 fzstd@0.1.1)
tools_dir=$ZHF_ROOT/tools/node
for tool in "${tools[@]}"; do
  name=${tool%@*} version=${tool##*@}
  if ! grep -qs "\"version\": \"$version\"" "$tools_dir/node_modules/$name/package.json"; then
    echo "zhf setup_web: installing ${tools[*]} into tools/node"
    mkdir -p "$tools_dir"
    npm install --prefix "$tools_dir" --no-audit --no-fund --loglevel=error "${tools[@]}" >/dev/null
    break
  fi
done
