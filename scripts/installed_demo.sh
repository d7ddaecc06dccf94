#!/usr/bin/env bash
# The demo's run: renders a synthetic scene, then runs feature extraction,
# gcn_matcher and the mapper on it, and prints the result table. Installed as
# <prefix>/share/colmap-gcn/demo.sh, where nothing is needed beyond the
# installed files and COLMAP; scripts/demo.sh runs it from the source tree
# after building, on a larger scene.
#   usage: demo.sh [output folder, default ./colmap-gcn-demo] [gcn_reconstructor options...]
# DEMO_SCENE (default <output folder>/scene) and DEMO_SYNTH_ARGS (default
# 24 images) choose the scene's folder and its gcn_synth flags.
set -euo pipefail
here="$(cd "$(dirname "$(readlink -f "$0")")" && pwd)"
prefix="$(cd "$here/../.." && pwd)"
# The installed front end under the name `colmap`, as the docs type it; the
# real COLMAP is found further down PATH. From the source tree, the caller
# has put build/bin first.
if [ -x "$prefix/lib/colmap-gcn/colmap" ]; then
  export PATH="$prefix/lib/colmap-gcn:$PATH"
fi

out="${1:-colmap-gcn-demo}"
shift || true
scene="${DEMO_SCENE:-$out/scene}"
read -r -a synth_args <<< "${DEMO_SYNTH_ARGS:---GcnSynth.num_images 24}"
work="$out/workspace"
rm -rf "$work"
if [ ! -d "$scene/images" ]; then
  colmap gcn_synth --output_path "$scene" --GcnSynth.family ordinary \
    "${synth_args[@]}" --GcnSynth.seed 1
fi
# The rendered images carry no EXIF: pass the known pinhole intrinsics, as
# for a calibrated camera (cameras.txt: ID MODEL WIDTH HEIGHT fx fy cx cy).
params=$(awk '!/^#/ && NF >= 8 {print $5","$6","$7","$8; exit}' "$scene/gt/cameras.txt")
colmap gcn_reconstructor --image_path "$scene/images" --workspace_path "$work" \
  --ImageReader.single_camera 1 --ImageReader.camera_model PINHOLE \
  --ImageReader.camera_params "$params" \
  --SiftExtraction.max_num_features 2048 --Mapper.num_threads 1 "$@"
