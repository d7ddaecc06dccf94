#!/usr/bin/env bash
# The whole test suite on a fresh Debian 12 machine: install, build, ctest.
# Runs every tier (ctest labels unit, colmap, data; docs/architecture.md);
# extra arguments go to ctest, e.g. `-L unit` for the fast tier only.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
