#!/usr/bin/env bash
# Installs the Debian packages granflow needs (only those missing) and builds it in build/.
set -euo pipefail
cd "$(dirname "$0")/.."
# libopenblas0-serial replaces the reference BLAS that petsc-dev brings (Debian's alternatives pick
# it): MUMPS's dense kernels, the coupled solve's cost, run twice as fast with it (docs/benchmarks.md).
# strace fails the file system's writes in the test of a checkpoint on a full disk (tests/cli.cmake).
packages=(build-essential cmake ninja-build pkg-config petsc-dev libtomlplusplus-dev libcli11-dev libfmt-dev
          zlib1g-dev libgtest-dev libbenchmark-dev openmpi-bin python3-numpy python3-matplotlib libopenblas0-serial
          strace)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq "${missing[@]}" > /dev/null
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build
