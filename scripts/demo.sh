#!/usr/bin/env bash
# The main job on a built-in default: renders a synthetic scene, then runs
# feature extraction, gcn_matcher and the mapper on it with our `colmap`
# front end, and prints the result table. Everything goes under ./demo.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh >/dev/null
export PATH="$PWD/build/bin:$PATH"

scene=demo/scene
work=demo/workspace
rm -rf "$work"
if [ ! -d "$scene/images" ]; then
  colmap gcn_synth --output_path "$scene" --GcnSynth.family ordinary \
    --GcnSynth.num_images 24 --GcnSynth.seed 1
fi
# The rendered images carry no EXIF: pass the known pinhole intrinsics, as
# for a calibrated camera (cameras.txt: ID MODEL WIDTH HEIGHT fx fy cx cy).
params=$(awk '!/^#/ && NF >= 8 {print $5","$6","$7","$8; exit}' "$scene/gt/cameras.txt")
colmap gcn_reconstructor --image_path "$scene/images" --workspace_path "$work" \
  --ImageReader.single_camera 1 --ImageReader.camera_model PINHOLE \
  --ImageReader.camera_params "$params" \
  --SiftExtraction.max_num_features 2048 --Mapper.num_threads 1 "$@"
