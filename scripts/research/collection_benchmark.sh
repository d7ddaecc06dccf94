#!/usr/bin/env bash
# A 1DSfM-style collection benchmark (docs/benchmarks.md): photos of
# unrelated places in one database, matched by each method, against each
# place reconstructed alone with exhaustive matching.
#
#   scripts/research/collection_benchmark.sh OUT METHODS SCENE_DIR... [-- OPTION...]
#
# SCENE_DIRs are image-folder scenes with one parent (e.g. ../shared/
# datasets/books); METHODS a gcn_benchmark method list (e.g.
# gcn,adaptive,graphmatch,knn:10). OPTIONs go to every gcn_benchmark run
# (--SiftExtraction.*, --SiftMatching.*, --GcnMatching.*, --Benchmark.*;
# the first run sets --Benchmark.keep_going itself).
# Scenes whose pairs could not be labelled alone (e.g. no model) are left
# out with a message. Three steps, each cached in OUT so that an
# interrupted run resumes:
#   OUT/alone/       every scene alone, exhaustive (features, labels and the
#                    registered images the collection is compared against);
#   OUT/collection/  the scenes merged (scripts/research/merge_scenes.sh);
#   OUT/run/         the collection benchmarked with METHODS: report.md
#                    "Collection" gives cross-scene pairs, the estimated
#                    exhaustive time and each scene's registration.
# Environment: COLMAP_GCN_BUILD (default build).
set -euo pipefail
if [ "$#" -lt 4 ]; then
  echo "usage: $0 OUT METHODS SCENE_DIR SCENE_DIR... [-- OPTION...]" >&2
  exit 2
fi
source "$(dirname "$0")/common.sh"
# Back to the caller's directory: OPTIONs keep their relative paths.
cd "$CALLER_PWD"
OUT="$(from_caller "$1")"
METHODS="$2"
shift 2
SCENES=()
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
  SCENES+=("$(from_caller "$1")")
  shift
done
[ "$#" -gt 0 ] && shift
OPTIONS=("$@")
if [ ! -x "$COLMAP" ]; then
  echo "collection_benchmark: no $COLMAP (build first, or set COLMAP_GCN_BUILD)" >&2
  exit 1
fi
if [ "${#SCENES[@]}" -lt 2 ]; then
  echo "collection_benchmark: a collection needs at least two scenes" >&2
  exit 2
fi
PARENT="$(dirname "${SCENES[0]}")"
NAMES=()
for scene in "${SCENES[@]}"; do
  if [ "$(dirname "$scene")" != "$PARENT" ]; then
    echo "collection_benchmark: $scene is not in $PARENT (the scenes need one parent folder)" >&2
    exit 2
  fi
  if [ ! -d "$scene/images" ]; then
    echo "collection_benchmark: $scene has no images/ folder" >&2
    exit 2
  fi
  NAMES+=("$(basename "$scene")")
done
DATASETS="$(IFS=,; echo "${SCENES[*]}")"

echo "collection_benchmark: 1/3 ${#SCENES[@]} scenes alone, exhaustive"
# A scene whose labels could not be built alone (e.g. no exhaustive model)
# is left out of the collection (named below), not a reason to stop.
"$COLMAP" gcn_benchmark --datasets "$DATASETS" --methods exhaustive \
  --output_path "$OUT/alone" --Benchmark.keep_going 1 "${OPTIONS[@]}"
KEPT=()
for name in "${NAMES[@]}"; do
  if [ -f "$OUT/alone/$name/labels/labels.csv" ]; then
    KEPT+=("$name")
  else
    echo "collection_benchmark: $name left out: no labels alone (see $OUT/alone/report.md)" >&2
  fi
done
if [ "${#KEPT[@]}" -lt 2 ]; then
  echo "collection_benchmark: fewer than two scenes have labels alone" >&2
  exit 1
fi
NAMES=("${KEPT[@]}")

DATA="$OUT/collection"
SCENE_DIR="$OUT/run/collection"
if [ ! -f "$SCENE_DIR/extraction.json" ]; then
  echo "collection_benchmark: 2/3 merging"
  rm -rf "$DATA" "$SCENE_DIR"
  SHARED="$PARENT" "$REPO/scripts/research/merge_scenes.sh" "$DATA" "$OUT/alone" \
    "${NAMES[@]}"
  mkdir -p "$SCENE_DIR/labels"
  cp "$DATA/base.db" "$SCENE_DIR/base.db"
  cp "$DATA/labels/labels.csv" "$SCENE_DIR/labels/labels.csv"
  # The collection's features are its scenes': their extraction time.
  seconds=0
  for name in "${NAMES[@]}"; do
    s=$(sed -n 's/.*"seconds": *\([0-9.eE+-]*\).*/\1/p' \
      "$OUT/alone/$name/extraction.json")
    seconds=$(awk -v a="$seconds" -v b="${s:-0}" 'BEGIN { print a + b }')
  done
  # Written last: its presence marks the merge as complete.
  echo "{\"seconds\": $seconds, \"session\": \"merged\"}" \
    >"$SCENE_DIR/extraction.json"
fi

echo "collection_benchmark: 3/3 the collection with $METHODS"
"$COLMAP" gcn_benchmark --datasets "$DATA" --methods "$METHODS" \
  --output_path "$OUT/run" \
  --Benchmark.alone_results_path "$OUT/alone/results.json" "${OPTIONS[@]}"
echo "collection_benchmark: $OUT/run/report.md"
