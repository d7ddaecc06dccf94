# Sourced by scripts/leave_scene_out.sh and scripts/train_default_model.sh:
# the folds of the real labelled corpus (docs/model_card.md), fixed before
# any fold was trained: sizes spread over the folds, each fold one small,
# one mid-sized and one large scene. Needs CORPUS set.
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
