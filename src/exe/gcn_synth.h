#pragma once

namespace colmap_gcn {

// `colmap gcn_synth`: renders a synthetic scene with exact ground truth.
int RunGcnSynth(int argc, char** argv);

}  // namespace colmap_gcn
