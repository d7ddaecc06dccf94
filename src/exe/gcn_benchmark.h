#pragma once

#include <memory>
#include <string>
#include <vector>

#include "feature/pairing.h"
#include "scene/database.h"

namespace colmap_gcn {

// Builds a pair generator from --GcnMatching.* arguments exactly as
// `colmap gcn_matcher` would (every option it registers); the benchmark's
// PairGeneratorFactory.
std::unique_ptr<PairGenerator> CreatePairGeneratorFromArguments(
    const std::vector<std::string>& gcn_matching_args,
    const Database& database);

// `colmap gcn_benchmark`: the paper's tables on any scene in one command.
int RunGcnBenchmark(int argc, char** argv);

}  // namespace colmap_gcn
