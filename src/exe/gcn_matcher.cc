#include "exe/gcn_matcher.h"

#include "controllers/gcn_matching.h"
#include "util/error.h"
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
      "pairs per COLMAP matching run (each commits; resume granularity)");
  manager->AddDefaultOption("GcnMatching.pairs_path",
                            &matching.pairs_path,
                            "where the chosen pairs are written");
  manager->AddDefaultOption("GcnMatching.colmap_log_path",
                            &matching.colmap_log_path,
                            "log of COLMAP's full output");
  manager->AddDefaultOption(
      "GcnMatching.verbose", &matching.verbose, "show all of COLMAP's output");
  manager->AddDefaultOption("GcnMatching.filter_lookalikes",
                            &options->filter_lookalikes,
                            "hide look-alike (duplicate structure) pairs from "
                            "the mapper after matching (docs/lookalike.md)");
  manager->AddDefaultOption("SiftMatching.min_num_inliers",
                            &matching.min_num_inliers,
                            "COLMAP's verification threshold; also what a "
                            "verified pair (UM) needs");
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
  PrintGcnMatchingReport(RunGcnMatching(database_path, options));
  return 0;
}

}  // namespace colmap_gcn
