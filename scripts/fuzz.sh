#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz into build-fuzz (clang, ASan +
# UBSan) and runs each for SECONDS (default 60), one after the other.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]     e.g. scripts/fuzz.sh 600 bundler_fuzzer
#
# Every target starts from its seed corpus (tests/fuzz/corpus/<target>, which
# must still parse: checked first) plus what earlier runs found
# (build-fuzz/corpus/<target>). Prints per target the executions, exec/s,
# coverage and whether it crashed; a crashing input is kept in
# build-fuzz/artifacts/<target>/ and the script exits 1. Logs:
# build-fuzz/logs/<target>.log. Runs under `nice -n 10`.
set -euo pipefail
cd "$(dirname "$0")/.."

SECONDS_PER_TARGET=60
if [ $# -gt 0 ] && [[ "$1" =~ ^[0-9]+$ ]]; then
  SECONDS_PER_TARGET=$1
  shift
fi
ALL_TARGETS=(model_file_fuzzer pairs_file_fuzzer hdf5_descriptors_fuzzer
  npy_descriptors_fuzzer text_descriptors_fuzzer sparse_model_binary_fuzzer
  sparse_model_text_fuzzer bundler_fuzzer)
if [ $# -gt 0 ]; then
  TARGETS=("$@")
else
  TARGETS=("${ALL_TARGETS[@]}")
fi
for target in "${TARGETS[@]}"; do
  if [ ! -d "tests/fuzz/corpus/$target" ]; then
    echo "ERROR: unknown fuzz target $target (known: ${ALL_TARGETS[*]})" >&2
    exit 2
  fi
done

BUILD=build-fuzz
if ! command -v clang++ >/dev/null; then
  echo "ERROR: clang++ not found (scripts/install_deps.sh installs it)" >&2
  exit 2
fi
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCOLMAP_GCN_BUILD_FUZZERS=ON -DCOLMAP_GCN_BUILD_TESTS=OFF \
    -DCOLMAP_GCN_BUILD_BENCHMARKS=OFF >/dev/null
fi
nice -n 10 cmake --build "$BUILD" -j"$(nproc)" --target "${TARGETS[@]}" >/dev/null

mkdir -p "$BUILD/logs"
failed=0
printf '%-28s %8s %12s %8s %6s %6s  %s\n' target seconds executions exec/s cov ft result
for target in "${TARGETS[@]}"; do
  binary="$BUILD/bin/$target"
  seeds="tests/fuzz/corpus/$target"
  corpus="$BUILD/corpus/$target"
  artifacts="$BUILD/artifacts/$target"
  log="$BUILD/logs/$target.log"
  mkdir -p "$corpus" "$artifacts"

  # Seeds must parse: a reader change that rejects them would leave the
  # fuzzer mutating only garbage.
  if ! COLMAP_GCN_FUZZ_EXPECT_VALID=1 "$binary" "$seeds"/* >"$log" 2>&1; then
    printf '%-28s %s\n' "$target" "seed corpus rejected, see $log"
    failed=1
    continue
  fi

  # libhdf5 on corrupt files (docs/reliability.md): its own leaks are
  # suppressed (tests/fuzz/hdf5_lsan.supp), and its malloc of impossible
  # sizes read from the file returns NULL as glibc's does (HDF5 then reports
  # an error) instead of aborting; operator new, which our code uses, still
  # aborts on failure.
  # Its metadata cache also mallocs gigabytes it never touches, so only the
  # RSS limit applies to that target, not libFuzzer's per-malloc limit.
  lsan_options=""
  asan_options=""
  malloc_limit=2048
  if [ "$target" = hdf5_descriptors_fuzzer ]; then
    lsan_options="suppressions=$PWD/tests/fuzz/hdf5_lsan.supp"
    asan_options="allocator_may_return_null=1"
    malloc_limit=1048576
  fi
  # New inputs go to the first corpus directory, never into the repo.
  status=0
  LSAN_OPTIONS="$lsan_options" ASAN_OPTIONS="$asan_options" nice -n 10 "$binary" -max_total_time="$SECONDS_PER_TARGET" -timeout=10 \
    -rss_limit_mb=2048 -malloc_limit_mb="$malloc_limit" -print_final_stats=1 \
    -artifact_prefix="$artifacts/" "$corpus" "$seeds" >"$log" 2>&1 || status=$?

  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  elapsed=$(sed -n 's/.*Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  if [ "$status" -eq 0 ]; then
    result="ok, no crash"
  else
    failed=1
    artifact=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -1)
    kind=$(grep -m1 -oE 'ERROR: [A-Za-z]+: [^ ]*|runtime error: .*|deadly signal|out-of-memory[^)]*\)|timeout' "$log" || true)
    result="CRASH (${kind:-exit $status}) ${artifact:-see $log}"
  fi
  printf '%-28s %8s %12s %8s %6s %6s  %s\n' "$target" "${elapsed:-?}" \
    "${executions:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" "$result"
done
exit "$failed"
