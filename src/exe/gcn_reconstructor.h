#pragma once

namespace colmap_gcn {

// `colmap gcn_reconstructor`: feature_extractor -> gcn_matcher -> mapper in
// one command, with a summary of what each step cost and produced.
int RunGcnReconstructor(int argc, char** argv);

}  // namespace colmap_gcn
