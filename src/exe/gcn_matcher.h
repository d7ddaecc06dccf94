#pragma once

namespace colmap_gcn {

// `colmap gcn_matcher`: selects image pairs and matches them with COLMAP.
int RunGcnMatcher(int argc, char** argv);

}  // namespace colmap_gcn
