#!/usr/bin/env bash
# Reproduces docs/benchmarks.md: the paper's tables on every shared real
# scene with ground truth and on the three synthetic families, in one run
# (methods interleaved per scene, so matching times are comparable).
#
#   scripts/research/benchmark_all.sh [OUTPUT_DIR] [extra gcn_benchmark options...]
#
# OUTPUT_DIR defaults to benchmark-out/ (cached: rerunning resumes; use a
# fresh folder to re-measure times). COLMAP_GCN_BUILD selects the build
# folder (default: build); SHARED the shared datasets folder (default:
# ../shared/datasets). Methods not available in this build are reported as
# such. Run scripts/build.sh first.
#
# The ambiguous real scenes (books, cereal, oats, street) have no ground
# truth of their own: scripts/research/ambiguous_references.sh builds stand-in GT
# cameras for them into AMBIGUOUS (default ambiguous-scenes/), and they are
# benchmarked when that has been run.
set -euo pipefail
source "$(dirname "$0")/common.sh"
OUT="${1:-benchmark-out}"
shift || true

DATASETS=""
for scene in fountain-P11 entry-P10 temple-sparse-ring dino-sparse-ring; do
  if [ -d "$SHARED/$scene/gt" ]; then
    DATASETS="$DATASETS${DATASETS:+,}$SHARED/$scene"
  else
    echo "benchmark_all: $SHARED/$scene not found, skipped" >&2
  fi
done
AMBIGUOUS="${AMBIGUOUS:-ambiguous-scenes}"
for scene in books cereal oats street; do
  if [ -f "$AMBIGUOUS/$scene/gt/images.txt" ]; then
    DATASETS="$DATASETS${DATASETS:+,}$AMBIGUOUS/$scene"
  else
    echo "benchmark_all: $AMBIGUOUS/$scene/gt not found (run" \
      "scripts/research/ambiguous_references.sh), skipped" >&2
  fi
done
DATASETS="$DATASETS${DATASETS:+,}synth:ordinary:24:1,synth:repetitive:24:1,synth:symmetric:24:1"

METHODS="exhaustive,knn:5,knn:10,knn:25,knn:50,knn:100"
METHODS="$METHODS,vocab_tree:5,vocab_tree:10,vocab_tree:25,vocab_tree:50,vocab_tree:100"
METHODS="$METHODS,gcn,oracle"

exec "$COLMAP" gcn_benchmark \
  --datasets "$DATASETS" \
  --methods "$METHODS" \
  --output_path "$OUT" \
  --Benchmark.mapper_num_threads 1 \
  --SiftExtraction.num_threads 2 \
  --SiftMatching.num_threads 2 \
  "$@"
