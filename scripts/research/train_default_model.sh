#!/usr/bin/env bash
# Trains the default GCN model from scratch (docs/model_card.md): the real
# labelled corpus (scripts/research/label_real_corpus.sh) -> VLAD embedding + a
# small GCN on scale-free node features (scripts/research/corpus_folds.sh) -> model
# file.
#
#   scripts/research/train_default_model.sh [CORPUS] [MODEL_PATH] [extra gcn_train flags...]
#
# CORPUS defaults to ../corpus beside the repository; MODEL_PATH to
# CORPUS/default.gcnmodel (pass colmap_gcn/models/default.gcnmodel to
# replace the shipped model). Deterministic for a given SEED (default 0),
# whatever the thread count.
#
# Scenes: the folds of scripts/research/leave_scene_out.sh; folds 0-3 train (each
# scene alone and all of them as one collection, pairs across scenes
# unrelated), fold 4 validates (early stopping, decision threshold). The
# held-out numbers of this recipe are scripts/research/leave_scene_out.sh's: every
# real scene is reported by a fold model that never saw it; this model has
# seen all but fold 4 and is not evaluated on them.
# Environment: COLMAP_GCN_BUILD (default build), SEED (0), THREADS (2).
set -euo pipefail
source "$(dirname "$0")/common.sh"
CORPUS="$(from_caller "${1:-$REPO/../corpus}")"
MODEL="$(from_caller "${2:-$CORPUS/default.gcnmodel}")"
shift $(($# < 2 ? $# : 2))

if [ ! -d "$CORPUS" ]; then
  echo "train_default_model: $CORPUS not found (build it with scripts/research/label_real_corpus.sh)" >&2
  exit 1
fi
source "$REPO/scripts/research/corpus_folds.sh"
TRAIN_SCENES="${FOLDS[0]},${FOLDS[1]},${FOLDS[2]},${FOLDS[3]}"
VALIDATION_SCENES="${FOLDS[4]}"
TRAIN="$(present "$TRAIN_SCENES")"
VALIDATION="$(present "$VALIDATION_SCENES")"

"$COLMAP" gcn_train \
  --benchmark_path "$CORPUS" \
  --scenes "$TRAIN,${TRAIN//,/+}" \
  --validation_scenes "$VALIDATION" \
  --output_path "$MODEL" \
  "${GCN_TRAIN_FLAGS[@]}" \
  "$@"
