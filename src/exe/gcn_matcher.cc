#include "exe/gcn_matcher.h"

#include "controllers/colmap_runner.h"
#include "controllers/gcn_matching.h"
#include "controllers/pair_generators.h"
#include "evaluation/view_graph_figure.h"
#include "pairing/pairs_io.h"
#include "scene/database.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {

void AddGcnMatchingOptions(OptionManager* manager,
                           GcnMatchingOptions* options) {
  manager->AddDefaultOption("GcnMatching.pairing",
                            &options->pairing,
                            StringJoin(PairGenerators().Names(), " | "));
  PairGenerators().AddOptions(manager, &options->generators);
  GcnMatchingOptions::Matching& matching = options->matching;
  manager->AddDefaultOption(
      "GcnMatching.block_size",
      &matching.block_size,
      "most pairs per COLMAP matching run (each commits; resume "
      "granularity); runs are a tenth of the pairs, at least 100");
  manager->AddDefaultOption("GcnMatching.pairs_path",
                            &matching.pairs_path,
                            "where the chosen pairs are written");
  manager->AddDefaultOption("GcnMatching.colmap_log_path",
                            &matching.colmap_log_path,
                            "log of COLMAP's full output");
  manager->AddDefaultOption(
      "GcnMatching.verbose", &matching.verbose, "show all of COLMAP's output");
  manager->AddDefaultOption("GcnMatching.write_figures",
                            &matching.write_figures,
                            "write a PNG of the view graph next to the "
                            "pairs file");
  manager->AddDefaultOption("GcnMatching.filter_lookalikes",
                            &options->filter_lookalikes,
                            "hide look-alike (duplicate structure) pairs from "
                            "the mapper after matching (docs/lookalike.md); "
                            "0: off");
  manager->AddDefaultOption(
      "PairFilter.check_trusted_focal",
      &options->lookalike_filter.check_trusted_focal,
      "the look-alike filter checks trusted (EXIF) focal lengths against "
      "the view graph's loops; 0: uses them as they are");
  manager->AddDefaultOption("SiftMatching.min_num_inliers",
                            &matching.min_num_inliers,
                            "COLMAP's verification threshold; also what a "
                            "verified pair (UM) needs");
}

std::string ViewGraphFigurePath(const std::string& database_path,
                                const GcnMatchingOptions& options) {
  std::string path = options.matching.pairs_path.empty()
                         ? database_path + ".pairs.txt"
                         : options.matching.pairs_path;
  if (path.size() > 4 && path.compare(path.size() - 4, 4, ".txt") == 0) {
    path.resize(path.size() - 4);
  }
  return path + "_view_graph.png";
}

std::string WriteGcnMatchingFigure(const std::string& database_path,
                                   const GcnMatchingOptions& options) {
  if (!options.matching.write_figures) return "";
  const std::string pairs_path = options.matching.pairs_path.empty()
                                     ? database_path + ".pairs.txt"
                                     : options.matching.pairs_path;
  MatchedViewGraph graph = ReadMatchedViewGraph(
      database_path, pairs_path, options.matching.min_num_inliers);
  graph.title = "View graph of " + options.pairing + " pairing";
  const std::string path = ViewGraphFigurePath(database_path, options);
  WriteMatchedViewGraphImage(path, graph);
  LOG(INFO) << "view graph picture: " << path;
  return path;
}

int RunGcnMatcher(int argc, char** argv) {
  std::string database_path;
  GcnMatchingOptions options;
  OptionManager manager(
      "gcn_matcher",
      "Chooses the image pairs worth matching and matches them with COLMAP's "
      "own matcher and geometric verification.");
  manager.AddRequiredOption("database_path", &database_path);
  AddGcnMatchingOptions(&manager, &options);
  manager.AddPassThroughPrefix("SiftMatching.");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  options.colmap_args = manager.PassThroughArguments();
  manager.Check([&] { options.Check(); });
  CheckColmapArguments(options.colmap_args);
  PrintGcnMatchingReport(RunGcnMatching(database_path, options));
  WriteGcnMatchingFigure(database_path, options);
  return 0;
}

}  // namespace colmap_gcn
