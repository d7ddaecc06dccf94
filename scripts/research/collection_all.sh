#!/usr/bin/env bash
# The 1DSfM-scale collection of docs/benchmarks.md: every shared real scene
# (../shared/datasets, about 1,200 photos of 29 unrelated places) merged
# into one database and paired by each method, against each scene matched
# alone exhaustively. One command over scripts/research/collection_benchmark.sh.
#
#   scripts/research/collection_all.sh [OUT] [BENCHMARK_ALL_OUT]
#
# OUT defaults to collection-out/. BENCHMARK_ALL_OUT is an output folder of
# scripts/research/benchmark_all.sh (same 2048 features): the scenes it has
# matched exhaustively are copied into OUT/alone/ (features, labels and the
# exhaustive run; nothing there is changed) instead of being extracted and
# matched again. Hours of matching on two cores: run it in the background;
# a killed run resumes where it stopped. SHARED and COLMAP_GCN_BUILD as in
# scripts/research/common.sh; METHODS overrides the method list.
set -euo pipefail
source "$(dirname "$0")/common.sh"
OUT="$(from_caller "${1:-collection-out}")"
BENCH_ALL="${2:+$(from_caller "$2")}"
SHARED="$(realpath -m "$SHARED")"
if [ ! -d "$SHARED" ]; then
  echo "collection_all: $SHARED not found: nothing to merge" >&2
  exit 0
fi
METHODS="${METHODS:-knn:5,knn:10,vocab_tree:10,gcn,adaptive,graphmatch,oracle}"

SCENES=()
for images in "$SHARED"/*/images; do
  scene="$(dirname "$images")"
  name="$(basename "$scene")"
  SCENES+=("$scene")
  from="$BENCH_ALL/$name"
  to="$OUT/alone/$name"
  if [ -n "$BENCH_ALL" ] && [ -f "$from/exhaustive/result.json" ] &&
    [ ! -e "$to" ]; then
    mkdir -p "$to.tmp"
    cp -a "$from/base.db" "$from/extraction.json" "$from/labels" \
      "$from/exhaustive" "$to.tmp/"
    mv "$to.tmp" "$to"
    echo "collection_all: $name alone from $from"
  fi
done

exec "$REPO/scripts/research/collection_benchmark.sh" "$OUT" "$METHODS" \
  "${SCENES[@]}" -- \
  --SiftExtraction.max_num_features 2048 \
  --SiftExtraction.num_threads 2 \
  --SiftMatching.num_threads 2 \
  --Benchmark.mapper_num_threads 1
