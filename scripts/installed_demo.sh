#!/usr/bin/env bash
# The demo from an installed colmap-gcn (installed as
# <prefix>/share/colmap-gcn/demo.sh; scripts/demo.sh is the source-tree
# one): renders a synthetic scene, then runs feature extraction, gcn_matcher
# and the mapper on it, and prints the result table. Nothing is needed
# beyond the installed files and COLMAP.
#   usage: demo.sh [output folder, default ./colmap-gcn-demo] [gcn_reconstructor options...]
set -euo pipefail
here="$(cd "$(dirname "$(readlink -f "$0")")" && pwd)"
prefix="$(cd "$here/../.." && pwd)"
# The installed front end under the name `colmap`, as the docs type it; the
# real COLMAP is found further down PATH.
export PATH="$prefix/lib/colmap-gcn:$PATH"

out="${1:-colmap-gcn-demo}"
shift || true
scene="$out/scene"
work="$out/workspace"
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
