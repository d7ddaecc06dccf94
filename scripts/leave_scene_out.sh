#!/usr/bin/env bash
# Leave-one-scene-out evaluation over the shared real scenes with ground
# truth (docs/model_card.md): for each such scene, the default model's recipe
# trains a fold with the *other* ground-truth scenes added to its training
# set, and `colmap gcn_model_evaluator` scores the left-out scene with that
# fold's model. No scene is ever reported by a model that was trained on it.
#
#   scripts/leave_scene_out.sh [WORK_DIR]
#
# WORK_DIR (default train-work/, shared with scripts/train_default_model.sh)
# caches the prepared scenes; the folds' models and outputs are written to
# WORK_DIR/leave-scene-out/. Environment as for train_default_model.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
WORK="${1:-train-work}"
BUILD="${COLMAP_GCN_BUILD:-build}"
SHARED="${SHARED:-../shared/datasets}"
OUT="$WORK/leave-scene-out"
mkdir -p "$OUT"

SCENES=()
for scene in fountain-P11 entry-P10 temple-sparse-ring dino-sparse-ring; do
  if [ -d "$SHARED/$scene/gt" ]; then
    SCENES+=("$scene")
  else
    echo "leave_scene_out: $SHARED/$scene/gt not found, skipped" >&2
  fi
done
if [ "${#SCENES[@]}" -lt 2 ]; then
  echo "leave_scene_out: needs at least two scenes with ground truth" >&2
  exit 1
fi

for test in "${SCENES[@]}"; do
  others=""
  for scene in "${SCENES[@]}"; do
    [ "$scene" = "$test" ] || others="$others${others:+,}$scene"
  done
  echo "== fold $test: trained with $others" >&2
  GT_TRAIN="$others" GT_TEST="$test" scripts/train_default_model.sh \
    "$WORK" "$OUT/$test.gcnmodel" >"$OUT/$test.train.txt" 2>&1 ||
    { echo "leave_scene_out: fold $test failed, see $OUT/$test.train.txt" >&2; exit 1; }
  "$BUILD/bin/colmap" gcn_model_evaluator \
    --model_path "$OUT/$test.gcnmodel" \
    --benchmark_path "$WORK" \
    --scenes "$test" \
    --max_k 15 >"$OUT/$test.txt"
done

# One table per question, one row per left-out scene.
print_rows() {  # print_rows <table header prefix>
  local header="$1" first=1
  for test in "${SCENES[@]}"; do
    awk -v h="$header" -v first="$first" '
      index($0, h) == 1 { on = 1; if (first) print; next }
      on && /^\|---/ { if (first) print; next }
      on && /^\| / { print; next }
      on { on = 0 }' "$OUT/$test.txt"
    first=0
  done
}
echo "Leave-one-scene-out over ${SCENES[*]} (each row: the fold that never saw the scene)."
echo
echo "F against fixed k, and ranking AP:"
echo
print_rows "| scene | pairs | matchable |"
echo
echo "Best precision at recall >= 0.8 (threshold chosen with the labels):"
echo
print_rows "| scene | GCN | similarity |"
echo
for test in "${SCENES[@]}"; do
  grep -o "threshold [0-9.]*; seed" "$OUT/$test.train.txt" |
    sed "s/; seed//;s/^/$test fold: decision /"
done
