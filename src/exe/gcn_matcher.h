#pragma once

#include <string>
#include <vector>

#include "controllers/gcn_matching.h"
#include "util/option_manager.h"

namespace colmap_gcn {

// Registers the --GcnMatching.* options: --GcnMatching.pairing, every
// registered generator's (PairGenerators()) and the matching ones.
void AddGcnMatchingOptions(OptionManager* manager, GcnMatchingOptions* options);

// Where gcn_matcher's view-graph picture goes: beside the pairs file
// ("<pairs file without .txt>_view_graph.png").
std::string ViewGraphFigurePath(const std::string& database_path,
                                const GcnMatchingOptions& options);

// Writes the picture of the matched view graph (attempted / verified /
// rejected pairs, evaluation/view_graph_figure.h) when
// options.matching.write_figures; returns its path or "".
std::string WriteGcnMatchingFigure(const std::string& database_path,
                                   const GcnMatchingOptions& options);

// `colmap gcn_matcher`: selects image pairs and matches them with COLMAP.
int RunGcnMatcher(int argc, char** argv);

}  // namespace colmap_gcn
