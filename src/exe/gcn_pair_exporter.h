#pragma once

namespace colmap_gcn {

// `colmap gcn_pair_exporter`: the pairs any of our generators chooses,
// written without matching, in hloc's or COLMAP's pairs file layout.
int RunGcnPairExporter(int argc, char** argv);

}  // namespace colmap_gcn
