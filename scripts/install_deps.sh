#!/usr/bin/env bash
# Installs every Debian 12 package colmap-gcn needs to build, test and run.
# Idempotent and non-interactive; run as root (or with sudo available).
set -euo pipefail

PACKAGES=(
  # Toolchain and build.
  build-essential cmake git
  # COLMAP itself (3.8, CPU-only use) and the libraries its design card names.
  colmap libeigen3-dev libopencv-dev libceres-dev libsuitesparse-dev
  # Database access, options, result files (JSON), tests and benchmarks.
  libsqlite3-dev sqlite3 libboost-program-options-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # hloc global descriptors (HDF5); FAISS for approximate kNN at scale.
  libhdf5-dev libfaiss-dev
  # The PyTorch reference of the GCN (tests compare against it).
  python3 python3-numpy python3-torch
  # Measuring whole commands; formatting.
  hyperfine time clang-format
  # Rendering the HTML report in a real browser (tests/evaluation, headless).
  chromium
  # libFuzzer targets (scripts/fuzz.sh): clang and its compiler-rt runtimes.
  clang libclang-rt-14-dev
)

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  SUDO="sudo"
fi

missing=()
for package in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null |
      grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_deps: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install_deps: done"
