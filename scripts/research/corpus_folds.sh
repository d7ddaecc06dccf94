# Sourced by scripts/research/leave_scene_out.sh and scripts/research/train_default_model.sh:
# the recipe's gcn_train settings and the folds of the real labelled corpus
# (docs/model_card.md), the folds fixed before
# any fold was trained: sizes spread over the folds, each fold one small,
# one mid-sized and one large scene. Needs CORPUS, SEED and THREADS set.
FOLDS=(
  "entry-P10,dtu-scan37,bm-mold-gold-cape"
  "fountain-P11,fox,cup-desk"
  "dino-sparse-ring,box-office,can-tiles"
  "temple-sparse-ring,bm-ethiopian-head,figure-kitchen"
  "figurine,bm-mary-rose,giza-rooftop"
)

# present <comma list>: the scenes with labels in CORPUS, as a comma list;
# the others are named on stderr.
present() {
  local kept=""
  for scene in ${1//,/ }; do
    if [ -f "$CORPUS/$scene/labels/labels.csv" ]; then
      kept="$kept${kept:+,}$scene"
    else
      echo "$(basename "$0"): $scene has no labels in $CORPUS, left out" >&2
    fi
  done
  echo "$kept"
}

# The recipe's gcn_train settings: training QES k1 = 40 (on scenes of
# 10-150 images k1 = 100 would make most QESs the whole scene), also stored
# as the recommended test-time settings. The node features are only
# scale-free numbers (reciprocal_only: the query-scaled distance, the kNN
# ranks both ways and the neighbour overlaps; docs/gcn.md), so a small GCN
# (32-32-16-16, FC 16) with neighbour-mean aggregation, trained from a
# random start with Adam, is kept at the epoch with the best validation AP;
# the decision threshold maximises the mean F on the validation scenes.
GCN_TRAIN_FLAGS=(
  --GcnTraining.k1 40 --GcnTraining.k2 5 --GcnTraining.u 10
  --GcnTraining.test_k1 40 --GcnTraining.test_k2 5 --GcnTraining.test_u 5
  --GcnTraining.feature_scaling query
  --GcnTraining.structure_features reciprocal_only
  --GcnTraining.gcn_dims 32,32,16,16 --GcnTraining.fc_dim 16
  --GcnTraining.aggregation row
  --GcnTraining.initialization xavier
  --GcnTraining.optimizer adam --GcnTraining.learning_rate 0.001
  --GcnTraining.batch_size 8 --GcnTraining.num_epochs 12
  --GcnTraining.lr_decay_epochs 8,10
  --GcnTraining.positive_weight -1
  --GcnTraining.early_stopping_patience 4
  --GcnTraining.threshold -1
  --GcnTraining.seed "$SEED"
  --GcnTraining.num_threads "$THREADS"
)
