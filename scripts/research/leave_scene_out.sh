#!/usr/bin/env bash
# Leave-scene-out evaluation over the real labelled corpus
# (docs/real_corpus.md, docs/model_card.md): five rotating folds of real
# scenes; fold i is the test fold, fold i+1 validates (early stopping and
# the decision threshold), the other three train. Every scene is reported
# once, by the model of the fold that left it out, in one table
# (`colmap gcn_model_evaluator --folds_path`).
#
#   scripts/research/leave_scene_out.sh [CORPUS] [OUT] [extra gcn_train flags...]
#
# CORPUS (default ../corpus, built by scripts/research/label_real_corpus.sh) holds
# one labelled scene per folder; OUT (default CORPUS/leave-scene-out)
# receives fold<i>.gcnmodel, fold<i>.train.txt, folds.txt and table.md,
# collection.gcnmodel, collection.train.txt and collection.md.
# Training uses each training scene alone and all of them as one
# collection (pairs across scenes unrelated), so the model sees unrelated
# photos. Scenes missing from CORPUS are left out with a message. Folds
# whose model exists are not retrained (delete it to retrain).
# Environment: COLMAP_GCN_BUILD (default build), SEED (0), THREADS (2),
# ONNX_PATH (the network, for models trained with
# --GcnTraining.embedding onnx | vlad+onnx; passed to the evaluator),
# EXTRA_TRAIN (comma list of further scenes in CORPUS every fold trains on,
# e.g. synthetic ones; never evaluated here).
set -euo pipefail
source "$(dirname "$0")/common.sh"
CORPUS="$(from_caller "${1:-$REPO/../corpus}")"
OUT="$(from_caller "${2:-$CORPUS/leave-scene-out}")"
shift $(($# < 2 ? $# : 2))
EVAL_FLAGS=()
if [ -n "${ONNX_PATH:-}" ]; then EVAL_FLAGS=(--onnx_path "$ONNX_PATH"); fi

if [ ! -d "$CORPUS" ]; then
  echo "leave_scene_out: $CORPUS not found (build it with scripts/research/label_real_corpus.sh)" >&2
  exit 1
fi
source "$REPO/scripts/research/corpus_folds.sh"
NUM_FOLDS=${#FOLDS[@]}
for ((i = 0; i < NUM_FOLDS; ++i)); do
  FOLDS[$i]="$(present "${FOLDS[$i]}")"
done

# train_fold <model> <train scenes> <validation scenes> <log> [flags...]:
# trains unless the model exists.
train_fold() {
  local model="$1" train="$2" validation="$3" log="$4"
  shift 4
  [ -f "$model" ] && return 0
  "$COLMAP" gcn_train \
    --benchmark_path "$CORPUS" \
    --scenes "$train,${train//,/+}${EXTRA_TRAIN:+,$EXTRA_TRAIN}" \
    --validation_scenes "$validation" \
    --output_path "$model.tmp" \
    "${GCN_TRAIN_FLAGS[@]}" \
    "$@" >"$log" 2>&1 ||
    { echo "leave_scene_out: training $model failed, see $log" >&2; exit 1; }
  mv "$model.tmp" "$model"
}

mkdir -p "$OUT"
: >"$OUT/folds.txt.tmp"
for ((i = 0; i < NUM_FOLDS; ++i)); do
  test="${FOLDS[$i]}"
  validation="${FOLDS[$(((i + 1) % NUM_FOLDS))]}"
  train=""
  for ((j = 0; j < NUM_FOLDS; ++j)); do
    if [ "$j" -ne "$i" ] && [ "$j" -ne $(((i + 1) % NUM_FOLDS)) ]; then
      train="$train${train:+,}${FOLDS[$j]}"
    fi
  done
  if [ -z "$test" ] || [ -z "$validation" ]; then
    echo "leave_scene_out: fold $i has no labelled test or validation scene, skipped" >&2
    continue
  fi
  model="$OUT/fold$i.gcnmodel"
  echo "== fold $i: test $test | validation $validation | train $train" >&2
  train_fold "$model" "$train" "$validation" "$OUT/fold$i.train.txt" "$@"
  echo "$model $test" >>"$OUT/folds.txt.tmp"
done
mv "$OUT/folds.txt.tmp" "$OUT/folds.txt"

"$COLMAP" gcn_model_evaluator \
  --benchmark_path "$CORPUS" \
  --folds_path "$OUT/folds.txt" \
  --max_k 40 \
  --num_threads "$THREADS" \
  "${EVAL_FLAGS[@]}" \
  --output_path "$OUT/table.md"

# Unrelated photos: one collection of the scenes of folds 0 and 1.
collection="${FOLDS[0]},${FOLDS[1]}"
echo "== collection: test ${collection//,/+} | validation ${FOLDS[2]} | train ${FOLDS[3]},${FOLDS[4]}" >&2
train_fold "$OUT/collection.gcnmodel" "${FOLDS[3]},${FOLDS[4]}" "${FOLDS[2]}" \
  "$OUT/collection.train.txt" "$@"
"$COLMAP" gcn_model_evaluator \
  --benchmark_path "$CORPUS" \
  --model_path "$OUT/collection.gcnmodel" \
  --scenes "${collection//,/+}" \
  --max_k 40 \
  --num_threads "$THREADS" \
  "${EVAL_FLAGS[@]}" \
  --output_path "$OUT/collection.md"
