#!/usr/bin/env bash
# Reproduces docs/benchmarks.md: the paper's tables on every shared real
# scene with ground-truth cameras (gt/), smallest first, and on the three
# synthetic families, in one run (methods interleaved per scene, so matching
# times are comparable), at 2048 SIFT features per image.
#
#   scripts/research/benchmark_all.sh [OUTPUT_DIR] [extra gcn_benchmark options...]
#
# OUTPUT_DIR defaults to benchmark-out/ (cached: rerunning resumes; use a
# fresh folder to re-measure times). COLMAP_GCN_BUILD selects the build
# folder (default: build); SHARED the shared datasets folder (default:
# ../shared/datasets); SCENES a comma list of scene names to run instead of
# all (e.g. SCENES=figurine,dtu-scan37). Run scripts/build.sh first; then
# scripts/research/benchmark_docs.sh OUTPUT_DIR writes the tables into
# docs/benchmarks.md. The whole set is hours of matching on two cores: run
# it in the background; a killed run resumes where it stopped.
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
add_scene() {
  DATASETS="$DATASETS${DATASETS:+,}$1"
}
# The synthetic families first: small and independent of ../shared.
[ -n "${SCENES:-}" ] ||
  add_scene "synth:ordinary:24:1,synth:repetitive:24:1,synth:symmetric:24:1"
if [ -n "${SCENES:-}" ]; then
  IFS=, read -r -a names <<< "$SCENES"
  for scene in "${names[@]}"; do
    [ -d "$SHARED/$scene/gt" ] || { echo "benchmark_all: $SHARED/$scene/gt not found" >&2; exit 2; }
    add_scene "$SHARED/$scene"
  done
elif [ -d "$SHARED" ]; then
  # Every scene with ground truth, fewest images first, so that a run cut
  # short has complete tables for the scenes it finished.
  while read -r _ scene; do
    add_scene "$SHARED/$scene"
  done < <(for gt in "$SHARED"/*/gt; do
             scene="$(basename "$(dirname "$gt")")"
             echo "$(ls "$SHARED/$scene/images" | wc -l) $scene"
           done | sort -n -k1,1 -k2,2)
else
  echo "benchmark_all: $SHARED not found: synthetic scenes only" >&2
fi
AMBIGUOUS="${AMBIGUOUS:-ambiguous-scenes}"
for scene in books cereal oats street; do
  [ -n "${SCENES:-}" ] && break
  if [ -f "$AMBIGUOUS/$scene/gt/images.txt" ]; then
    add_scene "$AMBIGUOUS/$scene"
  else
    echo "benchmark_all: $AMBIGUOUS/$scene/gt not found (run" \
      "scripts/research/ambiguous_references.sh), skipped" >&2
  fi
done
# The fixed-k baselines of the paper's tables and the issue's targets
# (knn:5/10/25, vocab_tree:10/25), our pairings and the oracle.
METHODS="exhaustive,knn:5,knn:10,knn:25,vocab_tree:10,vocab_tree:25"
METHODS="$METHODS,gcn,adaptive,graphmatch,oracle"

exec "$COLMAP" gcn_benchmark \
  --datasets "$DATASETS" \
  --methods "$METHODS" \
  --output_path "$OUT" \
  --Benchmark.mapper_num_threads 1 \
  --SiftExtraction.num_threads 2 \
  --SiftMatching.num_threads 2 \
  --SiftExtraction.max_num_features 2048 \
  --Benchmark.keep_going 1 \
  "$@"
