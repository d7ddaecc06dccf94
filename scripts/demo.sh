#!/usr/bin/env bash
# The main job on a built-in scene: renders a synthetic scene of 80 images
# (400 x 300) orbiting a group of buildings -- most of its 3160 image pairs
# see different sides and share little -- then runs feature extraction, the
# pair selection of gcn_matcher and the mapper on it with our `colmap` front
# end. Ends with the pairs chosen next to exhaustive matching's count, the
# time saved, the registered images and the HTML report. Everything goes
# under ./demo.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
bash scripts/install_deps.sh
echo "demo: building (a first build takes a few minutes)"
bash scripts/build.sh >/dev/null
export PATH="$PWD/build/bin:$PATH"

scene=demo/scene80
work=demo/workspace
rm -rf "$work"
if [ ! -d "$scene/images" ]; then
  colmap gcn_synth --output_path "$scene" --GcnSynth.family ordinary \
    --GcnSynth.num_images 80 --GcnSynth.width 400 --GcnSynth.height 300 \
    --GcnSynth.seed 1
fi
# The rendered images carry no EXIF: pass the known pinhole intrinsics, as
# for a calibrated camera (cameras.txt: ID MODEL WIDTH HEIGHT fx fy cx cy).
params=$(awk '!/^#/ && NF >= 8 {print $5","$6","$7","$8; exit}' "$scene/gt/cameras.txt")
colmap gcn_reconstructor --image_path "$scene/images" --workspace_path "$work" \
  --ImageReader.single_camera 1 --ImageReader.camera_model PINHOLE \
  --ImageReader.camera_params "$params" \
  --SiftExtraction.max_num_features 2048 --Mapper.num_threads 1 "$@"
# The scene's ground truth: pairs whose images each see >= 30 % of what
# they share with the other (pair_overlap.csv: overlap12, overlap21), as
# gcn_synth counts them.
echo "  ground truth      $(awk -F, 'NR > 1 && $6 >= 0.3 && $7 >= 0.3' \
  "$scene/gt/pair_overlap.csv" | wc -l) of the pairs overlap by >= 30 % ($scene/gt/pair_overlap.csv)"
echo "  open the report   file://$PWD/$work/report.html"
echo "demo: done in $(( $(date +%s) - start )) s"
