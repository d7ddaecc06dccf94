#!/usr/bin/env bash
# Builds the real labelled corpus (docs/real_corpus.md): ground-truth pair
# labels for every shared real scene with gt/ cameras, smallest scene first,
# one scene per step.
#
#   scripts/label_real_corpus.sh [OUT]
#
# OUT defaults to ../corpus beside the repository (outside it). Per scene:
# `colmap gcn_benchmark --methods none` extracts capped SIFT features
# (--SiftExtraction.max_num_features 2048), matches only the pairs the pose
# filter keeps (--Benchmark.label_max_viewpoint_change_deg 70), triangulates
# the matches on the fixed GT cameras and writes OUT/<scene>/labels/labels.csv
# (CT >= tau_CT = 0.15: positive). A scene is complete when
# OUT/<scene>/corpus_complete.tsv exists (written atomically after its
# labels); complete scenes are skipped, so an interrupted run resumes, and
# matching resumes inside the scene's label database. Ends with one table
# (also OUT/corpus.md). Exits 0 without ../shared; 1 if a scene failed.
#
# Environment: COLMAP_GCN_BUILD (default build), SHARED (default
# ../shared/datasets), MAX_FEATURES (2048), MAX_VIEWPOINT_CHANGE (70; 0
# matches every pair), THREADS (2). Run it with `nice -n 19` beside other
# work.
set -euo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
OUT="$(realpath -m "${1:-$REPO/../corpus}")"
cd "$REPO"
BUILD="${COLMAP_GCN_BUILD:-build}"
SHARED="${SHARED:-../shared/datasets}"
MAX_FEATURES="${MAX_FEATURES:-2048}"
MAX_VIEWPOINT_CHANGE="${MAX_VIEWPOINT_CHANGE:-70}"
THREADS="${THREADS:-2}"
TAU_CT=0.15
COLMAP="$BUILD/bin/colmap"

if [ ! -d "$SHARED" ]; then
  echo "label_real_corpus: $SHARED not found, nothing to label" >&2
  exit 0
fi
if [ ! -x "$COLMAP" ]; then
  echo "label_real_corpus: $COLMAP not found (run scripts/build.sh)" >&2
  exit 1
fi
mkdir -p "$OUT"
exec 9>"$OUT/.lock"
if ! flock -n 9; then
  echo "label_real_corpus: another run is using $OUT" >&2
  exit 1
fi

SCENES="fountain-P11 entry-P10 temple-sparse-ring dino-sparse-ring
  bm-mold-gold-cape bm-mary-rose bm-ethiopian-head dtu-scan37 fox cup-desk
  can-tiles box-office figure-kitchen figurine giza-rooftop"

# Smallest first: "<images> <scene>" sorted by image count.
ORDERED=""
for scene in $SCENES; do
  if [ ! -f "$SHARED/$scene/gt/images.txt" ] &&
    [ ! -f "$SHARED/$scene/gt/images.bin" ]; then
    echo "label_real_corpus: $SHARED/$scene/gt not found, skipped" >&2
    continue
  fi
  n=$(find "$SHARED/$scene/images" -maxdepth 1 -type f | wc -l)
  ORDERED="$ORDERED$n $scene"$'\n'
done
ORDERED="$(printf '%s' "$ORDERED" | sort -n -k1,1 -k2,2 | awk '{print $2}')"

json_number() {  # json_number KEY FILE
  grep -o "\"$1\": *[-0-9.eE+]*" "$2" | head -1 | sed 's/.*: *//'
}

FAILED=""
for scene in $ORDERED; do
  dir="$OUT/$scene"
  marker="$dir/corpus_complete.tsv"
  if [ -f "$marker" ]; then
    echo "label_real_corpus: $scene complete, skipped" >&2
    continue
  fi
  mkdir -p "$dir"
  echo "label_real_corpus: $scene: labelling ($(date '+%F %T'))" >&2
  start=$(date +%s.%N)
  status=0
  "$COLMAP" gcn_benchmark \
    --datasets "$SHARED/$scene" \
    --methods none \
    --output_path "$OUT" \
    --Benchmark.tau_ct "$TAU_CT" \
    --Benchmark.label_max_viewpoint_change_deg "$MAX_VIEWPOINT_CHANGE" \
    --SiftExtraction.max_num_features "$MAX_FEATURES" \
    --SiftExtraction.num_threads "$THREADS" \
    --SiftMatching.num_threads "$THREADS" >"$dir/corpus_run.log" 2>&1 ||
    status=$?
  # Every attempt's wall time counts: a resumed scene sums its runs.
  awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN {printf "%.1f\n", e - s}' \
    >>"$dir/corpus_seconds.txt"
  labels="$dir/labels/labels.csv"
  record="$dir/labels/matching/label_matching.json"
  if [ "$status" -ne 0 ] || [ ! -f "$labels" ] || [ ! -f "$record" ]; then
    echo "label_real_corpus: $scene FAILED (see $dir/corpus_run.log)" >&2
    tail -n 3 "$dir/corpus_run.log" >&2 || true
    FAILED="$FAILED $scene"
    continue
  fi
  images=$(json_number num_images "$record")
  gt_images=$(json_number num_gt_images "$record")
  total=$(json_number pairs_total "$record")
  matched=$(json_number pairs_matched "$record")
  positives=$(awk -F, -v tau="$TAU_CT" \
    'p && $4 + 0 >= tau {n++} /^name1,/ {p = 1} END {print n + 0}' "$labels")
  labelled=$((gt_images * (gt_images - 1) / 2))
  negatives=$((labelled - positives))
  unlabelled=$((total - labelled))
  seconds=$(awk '{s += $1} END {printf "%.0f", s}' "$dir/corpus_seconds.txt")
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$scene" "$images" "$total" \
    "$matched" "$positives" "$negatives" "$unlabelled" "$seconds" \
    >"$marker.tmp"
  mv "$marker.tmp" "$marker"
  echo "label_real_corpus: $scene done: $(cat "$marker")" >&2
done

{
  echo "| scene | images | pairs total | pairs matched | positives | negatives | unlabelled | seconds |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|"
  for scene in $ORDERED; do
    marker="$OUT/$scene/corpus_complete.tsv"
    if [ -f "$marker" ]; then
      awk -F'\t' '{printf "| %s | %s | %s | %s | %s | %s | %s | %s |\n",
        $1, $2, $3, $4, $5, $6, $7, $8}' "$marker"
    else
      echo "| $scene | not labelled | | | | | | |"
    fi
  done
} | tee "$OUT/corpus.md"
if [ -n "$FAILED" ]; then
  echo "label_real_corpus: failed:$FAILED" >&2
  exit 1
fi
