#pragma once

#include <string>
#include <vector>

#include "controllers/gcn_matching.h"
#include "util/option_manager.h"

namespace colmap_gcn {

// Registers the --GcnMatching.* options: --GcnMatching.pairing, every
// registered generator's (PairGenerators()) and the matching ones.
void AddGcnMatchingOptions(OptionManager* manager, GcnMatchingOptions* options);

// `colmap gcn_matcher`: selects image pairs and matches them with COLMAP.
int RunGcnMatcher(int argc, char** argv);

}  // namespace colmap_gcn
