#pragma once

namespace colmap_gcn {

// `colmap gcn_train`: trains the embedding and the GCN on labelled scenes
// and writes a model file for `gcn_matcher --GcnMatching.model_path`.
int RunGcnTrain(int argc, char** argv);

}  // namespace colmap_gcn
