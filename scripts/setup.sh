#!/usr/bin/env bash
# Installs the Debian packages zhf needs (when run as root), then configures the Release build.
# Sourced by main.sh, test.sh and the bench scripts, which build what they need; safe to run again
# (it only does what is missing). ZHF_SETUP chooses: main (scripts/main.sh) the main job's
# packages and a build of the zhf binary alone (no tests, Python module or benchmark programs);
# python (scripts/install_python.sh) those and the Python module's; all (the default) everything.
set -euo pipefail

ZHF_ROOT=$(cd "$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")/.." && pwd)
ZHF_BUILD=${ZHF_BUILD_DIR:-$ZHF_ROOT/build}
ZHF_JOBS=$(nproc)

# The zhf binary and its main job (generate, verify on Vulkan: lavapipe without a GPU).
packages=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev libnlopt-cxx-dev libcli11-dev nlohmann-json3-dev zlib1g-dev libzstd-dev libwebp-dev
  glslang-tools spirv-tools libvulkan-dev mesa-vulkan-drivers
  libhealpix-cxx-dev libcfitsio-dev
)
cmake_options=(-DZHF_TESTS=OFF -DZHF_PYTHON=OFF -DZHF_BENCH=OFF)
if [ "${ZHF_SETUP:-all}" = python ]; then
  packages+=(python3 python3-dev pybind11-dev python3-numpy)
  cmake_options=(-DZHF_PYTHON=ON)
elif [ "${ZHF_SETUP:-all}" != main ]; then
  # The tests (a clang build with sanitizers and libFuzzer, GoogleTest, the aarch64 cross build
  # under qemu, libclang's bindings for check_one_place), the Python module and the benchmarks.
  packages+=(
    clang libclang-rt-14-dev libgtest-dev googletest libbenchmark-dev gnuplot-nox
    python3 python3-dev pybind11-dev python3-numpy python3-pytest python3-clang-14
    qemu-user g++-aarch64-linux-gnu libhwy-dev libxsimd-dev
  )
  cmake_options=(-DZHF_TESTS=ON -DZHF_PYTHON=ON -DZHF_BENCH=ON)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -eq 0 ]; then
    echo "zhf setup: installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  else
    echo "zhf setup: missing Debian packages: ${missing[*]} (run as root, or: sudo apt-get install ${missing[*]})" >&2
    exit 1
  fi
fi

# naga (wgpu's shader translator) as WebAssembly, pinned, into the project's own tools/node:
# zhf verify turns WGSL into SPIR-V with it under Node. Never installed globally.
naga_version=30.1.0
naga_dir=$ZHF_ROOT/tools/node
if ! grep -qs "\"version\": \"$naga_version\"" "$naga_dir/node_modules/naga-wasm/package.json"; then
  if ! command -v npm >/dev/null 2>&1 && [ "$(id -u)" -eq 0 ]; then
    echo "zhf setup: installing nodejs npm"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
  fi
  if command -v npm >/dev/null 2>&1; then
    echo "zhf setup: installing naga-wasm@$naga_version into tools/node"
    mkdir -p "$naga_dir"
    npm install --prefix "$naga_dir" --no-audit --no-fund --loglevel=error "naga-wasm@$naga_version" >/dev/null
  else
    echo "zhf setup: npm missing: WGSL kernels cannot be verified (install nodejs and npm)" >&2
  fi
fi

cmake -S "$ZHF_ROOT" -B "$ZHF_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DZHF_WERROR=ON "${cmake_options[@]}" >/dev/null
