#!/usr/bin/env bash
# The look-alike filter's fold check (docs/lookalike.md): each scene once
# with the filter off and once with it on, through gcn_benchmark (the second
# run reuses the first run's matches: the filter is applied to the cached
# databases and the mapper runs again).
#
#   scripts/research/lookalike_benchmark.sh OUTPUT_DIR METHODS DATASET...
#
# e.g. scripts/research/lookalike_benchmark.sh LK exhaustive AMB/books
# Writes OUTPUT_DIR/off.json and OUTPUT_DIR/on.json (copies of the two
# runs' results.json) and prints their table (lookalike_report.py).
#
# BENCH_ARGS (environment) adds gcn_benchmark flags to both runs, e.g.
# BENCH_ARGS="--ImageReader.camera_model PINHOLE --ImageReader.camera_params
# 640,640,320,240" gives a synthetic scene its true intrinsics as trusted
# (prior focal length), as EXIF does for photos.
set -euo pipefail
source "$(dirname "$0")/common.sh"
OUT="$(from_caller "$1")"
METHODS="$2"
shift 2
DATASETS=""
for d in "$@"; do DATASETS="${DATASETS:+$DATASETS,}$(from_caller "$d")"; done
mkdir -p "$OUT"
for filter in 0 1; do
  "$COLMAP" gcn_benchmark --datasets "$DATASETS" --methods "$METHODS" \
    --output_path "$OUT/bench" --GcnMatching.filter_lookalikes "$filter" \
    --Benchmark.mapper_num_threads 1 --SiftExtraction.num_threads 2 \
    --SiftMatching.num_threads 2 --SiftExtraction.max_num_features 2048 \
    ${BENCH_ARGS:-} > "$OUT/filter$filter.log" 2>&1
  cp "$OUT/bench/results.json" "$OUT/$([ "$filter" = 1 ] && echo on || echo off).json"
done
python3 scripts/research/lookalike_report.py "$OUT/off.json" "$OUT/on.json"
