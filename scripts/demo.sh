#!/usr/bin/env bash
# The main job on a built-in scene: renders a synthetic scene of 80 images
# (400 x 300) orbiting a group of buildings -- most of its 3160 image pairs
# see different sides and share little -- then runs feature extraction, the
# pair selection of gcn_matcher and the mapper on it with our `colmap` front
# end. Ends with the pairs chosen next to exhaustive matching's count, the
# time saved, the registered images and the HTML report. Everything goes
# under ./demo. The run itself is scripts/installed_demo.sh, the demo an
# installed colmap-gcn ships.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
bash scripts/install_deps.sh
echo "demo: building (a first build takes a few minutes)"
bash scripts/build.sh >/dev/null
export PATH="$PWD/build/bin:$PATH"

scene=demo/scene80
DEMO_SCENE="$scene" \
  DEMO_SYNTH_ARGS="--GcnSynth.num_images 80 --GcnSynth.width 400 --GcnSynth.height 300" \
  bash scripts/installed_demo.sh demo "$@"
work=demo/workspace
# The scene's ground truth: pairs whose images each see >= 30 % of what
# they share with the other (pair_overlap.csv: overlap12, overlap21), as
# gcn_synth counts them.
echo "  ground truth      $(awk -F, 'NR > 1 && $6 >= 0.3 && $7 >= 0.3' \
  "$scene/gt/pair_overlap.csv" | wc -l) of the pairs overlap by >= 30 % ($scene/gt/pair_overlap.csv)"
echo "  open the report   file://$PWD/$work/report.html"
echo "demo: done in $(( $(date +%s) - start )) s"
