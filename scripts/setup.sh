#!/usr/bin/env bash
# Installs the Debian packages zhf needs (when run as root), then configures the Release build.
# Sourced by main.sh and test.sh, which build what they need; safe to run again (it only does
# what is missing).
set -euo pipefail

ZHF_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ZHF_BUILD=${ZHF_BUILD_DIR:-$ZHF_ROOT/build}
ZHF_JOBS=$(nproc)

packages=(
  cmake ninja-build g++ clang libclang-rt-14-dev pkg-config
  libeigen3-dev libnlopt-cxx-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev
  glslang-tools spirv-tools libvulkan-dev mesa-vulkan-drivers
  libhealpix-cxx-dev gnuplot-nox
  python3 python3-dev pybind11-dev python3-numpy python3-pytest
)
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

cmake -S "$ZHF_ROOT" -B "$ZHF_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DZHF_WERROR=ON >/dev/null
