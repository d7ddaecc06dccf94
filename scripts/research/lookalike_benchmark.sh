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
# runs' results.json) and prints, per scene and method: verified pairs,
# wrong verified pairs reaching the mapper, pairs the filter removed (wrong
# / matchable by the labels), registered images, accurate cameras and the
# fraction of the circle the registered cameras cover (RingCoverage in
# evaluation/alignment.h; -1.00 from a build without it), against the
# ground truth's.
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
python3 - "$OUT/off.json" "$OUT/on.json" <<'PY'
import json, sys
for path in sys.argv[1:]:
    label = "filter on " if path.endswith("on.json") else "filter off"
    for scene in json.load(open(path))["scenes"]:
        for m in scene["methods"]:
            sfm = m.get("sfm", {})
            print(f'{scene["name"]:24s} {m["method"]:12s} {label}  UM {m["um"]:5d}  '
                  f'wrong verified {m["num_verified_wrong"]:4d}  removed '
                  f'{m.get("lookalike_removed", 0):4d} (wrong '
                  f'{m.get("lookalike_removed_wrong", 0)}, matchable '
                  f'{m.get("lookalike_removed_matchable", 0)})  registered '
                  f'{sfm.get("num_registered", "-")}/{scene["num_images"]}  accurate '
                  f'{sfm.get("pose_errors", {}).get("fraction_accurate", "-")}  '
                  f'ring {sfm.get("pose_errors", {}).get("ring_coverage", -1):.2f} '
                  f'(GT {sfm.get("pose_errors", {}).get("gt_ring_coverage", -1):.2f})  '
                  f'filter {m.get("filter_seconds", 0):.2f} s, pairing+matching '
                  f'{m["pairing_seconds"] + m["matching_seconds"]:.1f} s')
PY
