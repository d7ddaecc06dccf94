#pragma once

#include "controllers/gcn_matching.h"
#include "util/option_manager.h"

namespace colmap_gcn {

// Registers the --GcnMatching.* options (and passes --SiftMatching.* on).
void AddGcnMatchingOptions(OptionManager* manager, GcnMatchingOptions* options);

// `colmap gcn_matcher`: selects image pairs and matches them with COLMAP.
int RunGcnMatcher(int argc, char** argv);

}  // namespace colmap_gcn
