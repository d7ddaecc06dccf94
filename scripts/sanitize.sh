#!/usr/bin/env bash
# The unit tests under AddressSanitizer + UndefinedBehaviorSanitizer: builds
# them (RelWithDebInfo, no benchmarks) into build-asan and runs them with
# ctest. Any ASan report (out-of-bounds access, use after free, leak) or UBSan
# report fails the test that triggered it.
#
#   scripts/sanitize.sh [extra ctest arguments]
#
# Left out, for CI time (docs/reliability.md): the four suites that run the
# real COLMAP through whole pipelines on generated scenes (end-to-end,
# retrieval end-to-end, benchmark, synthetic-COLMAP); most of their time is
# COLMAP's own work, which is not instrumented. SANITIZE_ALL=1 runs them too.
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=build-asan
FLAGS="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCOLMAP_GCN_BUILD_TESTS=ON -DCOLMAP_GCN_BUILD_BENCHMARKS=OFF \
  -DCMAKE_CXX_FLAGS="$FLAGS" -DCMAKE_C_FLAGS="$FLAGS" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$BUILD" -j"$(nproc)"

# ctest names: whole-binary suites by target name, the rest Suite.Test.
EXCLUDE='^(e2e_test|retrieval_e2e_test|evaluation_benchmark_test|synthetic_colmap_test)$'
if [ "${SANITIZE_ALL:-0}" = 1 ]; then
  EXCLUDE='^$'
fi

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd "$BUILD"
ctest --output-on-failure -j"$(nproc)" -E "$EXCLUDE" "$@"
