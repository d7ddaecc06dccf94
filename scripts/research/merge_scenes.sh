#!/usr/bin/env bash
# Merges prepared scenes into one photo collection on disk, for SfM runs on
# it (docs/benchmarks.md); training and evaluation take the same collection
# in memory as "a+b+c" (docs/model_card.md).
#
#   scripts/research/merge_scenes.sh OUT BENCHMARK_DIR SCENE SCENE...
#
# BENCHMARK_DIR holds the scenes as `colmap gcn_benchmark` prepares them
# (<scene>/base.db, <scene>/labels/labels.csv). OUT (must not exist) gets
#   base.db             cameras, images, keypoints and descriptors of every
#                       scene, images renamed <scene>__<name>, no matches;
#   labels/labels.csv   each scene's labels; pairs across scenes unlisted,
#                       i.e. sharing nothing — true only if the scenes do;
#   images/             links to $SHARED/<scene>/images/* (default
#                       ../shared/datasets), for colmap mapper --image_path.
# With MATCHED=1, base.db is merged from each scene's exhaustive run
# (<scene>/exhaustive/database.db) with its matches kept: every pair within
# a scene matched, every pair across scenes unmatched, for replaying a
# pairing on the collection with colmap gcn_adaptive_simulator.
set -euo pipefail
if [ "$#" -lt 4 ]; then
  echo "usage: $0 OUT BENCHMARK_DIR SCENE SCENE..." >&2
  exit 2
fi
source "$(dirname "$0")/common.sh"
OUT="$(from_caller "$1")"
BENCH="$(from_caller "$2")"
shift 2
if [ -e "$OUT" ]; then
  echo "merge_scenes: $OUT exists" >&2
  exit 1
fi
SOURCE_DB=base.db
KEEP_MATCHES=0
if [ "${MATCHED:-0}" = 1 ]; then
  SOURCE_DB=exhaustive/database.db
  KEEP_MATCHES=1
fi
KINDS=""
for scene in "$@"; do
  labels="$BENCH/$scene/labels/labels.csv"
  if [ ! -f "$BENCH/$scene/$SOURCE_DB" ] || [ ! -f "$labels" ]; then
    echo "merge_scenes: $BENCH/$scene has no $SOURCE_DB and labels/labels.csv" >&2
    exit 1
  fi
  kinds=$(grep "^# kinds," "$labels" || true)
  if [ -z "$kinds" ] || { [ -n "$KINDS" ] && [ "$kinds" != "$KINDS" ]; }; then
    echo "merge_scenes: $labels: labels of another kind" >&2
    exit 1
  fi
  KINDS="$kinds"
done

mkdir -p "$OUT/labels" "$OUT/images"
DB="$OUT/base.db"
databases=""
prefixes=""
for scene in "$@"; do
  databases="${databases:+$databases,}$BENCH/$scene/$SOURCE_DB"
  prefixes="${prefixes:+$prefixes,}${scene}__"
done
"$COLMAP" gcn_merge_databases --database_paths "$databases" \
  --name_prefixes "$prefixes" --keep_matches "$KEEP_MATCHES" \
  --output_path "$DB" >/dev/null
LABELS="$OUT/labels/labels.csv"
PAIRS="$OUT/labels/pairs.tmp"
echo "# source,collection of $*" >"$LABELS"
echo "$KINDS" >>"$LABELS"
: >"$PAIRS"
for scene in "$@"; do
  labels="$BENCH/$scene/labels/labels.csv"
  awk -F, -v p="${scene}__" '$1 == "image" { print "image," p $2 }' \
    "$labels" >>"$LABELS"
  awk -F, -v p="${scene}__" 'pairs { print p $1 "," p $2 "," $3 "," $4 }
    $1 == "name1" { pairs = 1 }' "$labels" >>"$PAIRS"
  if [ -d "$SHARED/$scene/images" ]; then
    for image in "$SHARED/$scene/images"/*; do
      ln -s "$(readlink -f "$image")" "$OUT/images/${scene}__$(basename "$image")"
    done
  fi
done
echo "name1,name2,overlap,common_track_ratio" >>"$LABELS"
cat "$PAIRS" >>"$LABELS"
rm "$PAIRS"
echo "merge_scenes: $(sqlite3 "$DB" "select count(*) from images") images in $OUT"
