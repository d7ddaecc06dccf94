#pragma once

namespace colmap_gcn {

// `colmap gcn_benchmark`: the paper's tables on any scene in one command.
int RunGcnBenchmark(int argc, char** argv);

}  // namespace colmap_gcn
