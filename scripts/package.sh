#!/usr/bin/env bash
# Builds the Debian package dist/colmap-gcn_<version>_<arch>.deb: a Release
# build of the front end (tests and benchmarks off) into build-package, then
# CPack's DEB generator on the install rules (cmake/packaging.cmake; runtime
# dependencies from dpkg-shlibdeps, plus colmap).
#   BUILD_DIR=build bash scripts/package.sh   reuses an existing build tree
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build-package}"
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release \
    -DCOLMAP_GCN_BUILD_TESTS=OFF -DCOLMAP_GCN_BUILD_BENCHMARKS=OFF \
    "${launcher[@]}" >/dev/null
fi
# CPack installs without building every target first (tests, benchmarks):
# the package holds the front end only, built here.
cmake -S . -B "$build" -DCMAKE_SKIP_INSTALL_ALL_DEPENDENCY=ON >/dev/null
cmake --build "$build" -j"$(nproc)" --target colmap
# dpkg-shlibdeps (package dpkg-dev) derives the library dependencies.
command -v dpkg-shlibdeps >/dev/null ||
  { echo "package.sh: dpkg-shlibdeps missing (apt-get install dpkg-dev)" >&2; exit 1; }
dist="$PWD/dist"
mkdir -p "$dist"
rm -rf "$dist/_CPack_Packages"
(cd "$build" && cpack -G DEB -B "$dist" >/dev/null)
rm -rf dist/_CPack_Packages
deb=$(ls -t dist/colmap-gcn_*.deb | head -1)
echo "package.sh: $deb"
dpkg-deb --field "$deb" Package Version Architecture Depends
