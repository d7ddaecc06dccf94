#include "exe/gcn_matcher.h"

#include <cstdio>
#include <iostream>
#include <memory>

#include "controllers/colmap_runner.h"
#include "controllers/pair_matching.h"
#include "feature/pairing.h"
#include "scene/database.h"
#include "util/error.h"
#include "util/option_manager.h"
#include "util/timer.h"

namespace colmap_gcn {

namespace {

struct GcnMatchingOptions {
  // How pairs are chosen: exhaustive | imported.
  std::string pairing = "exhaustive";

  // Pairs file to import (pairing = imported).
  std::string match_list_path = "";

  // Where the chosen pairs are written; empty: "<database_path>.pairs.txt".
  std::string pairs_path = "";

  // Log of every COLMAP call with its full output; empty:
  // "<database_path>.colmap.log".
  std::string colmap_log_path = "";

  // Show all of COLMAP's output, not only progress.
  bool verbose = false;

  bool Check() const {
    return pairing == "exhaustive" ||
           (pairing == "imported" && !match_list_path.empty());
  }
};

std::unique_ptr<PairGenerator> CreatePairGenerator(
    const GcnMatchingOptions& options, const Database& database) {
  if (options.pairing == "exhaustive") {
    return std::make_unique<ExhaustivePairGenerator>(
        ExhaustiveMatchingOptions(), database);
  }
  ImagePairsMatchingOptions imported;
  imported.match_list_path = options.match_list_path;
  return std::make_unique<ImportedPairGenerator>(imported, database);
}

}  // namespace

int RunGcnMatcher(int argc, char** argv) {
  std::string database_path;
  GcnMatchingOptions options;
  OptionManager manager(
      "gcn_matcher",
      "Chooses the image pairs worth matching and matches them with COLMAP's "
      "own matcher and geometric verification.");
  manager.AddRequiredOption("database_path", &database_path);
  manager.AddDefaultOption(
      "GcnMatching.pairing", &options.pairing, "exhaustive | imported");
  manager.AddDefaultOption("GcnMatching.match_list_path",
                           &options.match_list_path,
                           "pairs file for pairing=imported");
  manager.AddDefaultOption("GcnMatching.pairs_path",
                           &options.pairs_path,
                           "where the chosen pairs are written");
  manager.AddDefaultOption("GcnMatching.colmap_log_path",
                           &options.colmap_log_path);
  manager.AddDefaultOption("GcnMatching.verbose", &options.verbose);
  manager.AddPassThroughPrefix("SiftMatching.");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  if (!options.Check()) {
    ThrowError("invalid --GcnMatching.pairing \"",
               options.pairing,
               "\" (exhaustive, or imported with "
               "--GcnMatching.match_list_path)");
  }

  const Timer total_timer;
  std::vector<ImagePair> pairs;
  size_t num_images = 0;
  {
    const Database database(database_path);
    num_images = database.NumImages();
    if (num_images < 2) {
      ThrowError(database_path,
                 " has ",
                 num_images,
                 " image(s); run colmap feature_extractor first");
    }
    pairs = CreatePairGenerator(options, database)->AllPairs();
  }
  const double pairing_seconds = total_timer.ElapsedSeconds();

  ColmapRunnerOptions runner_options;
  runner_options.log_path = options.colmap_log_path.empty()
                                ? database_path + ".colmap.log"
                                : options.colmap_log_path;
  runner_options.verbose = options.verbose;
  const ColmapRunner colmap(runner_options);

  PairMatchingOptions matching_options;
  matching_options.pairs_path = options.pairs_path;
  matching_options.colmap_args = manager.PassThroughArguments();
  std::cerr << "gcn_matcher: " << pairs.size() << " pairs from "
            << options.pairing << " pairing of " << num_images
            << " images; matching with COLMAP " << colmap.Version() << "\n";
  const PairMatchingSummary summary =
      MatchImagePairs(colmap, database_path, pairs, matching_options);

  std::printf("%-12s %8s %8s %8s %8s %10s %10s\n",
              "pairing",
              "images",
              "TAM",
              "UM",
              "UM/TAM",
              "pairing_s",
              "matching_s");
  std::printf("%-12s %8zu %8zu %8zu %8.3f %10.2f %10.2f\n",
              options.pairing.c_str(),
              num_images,
              summary.num_attempted_pairs,
              summary.num_verified_pairs,
              summary.UsefulRatio(),
              pairing_seconds,
              summary.matching_seconds);
  if (summary.num_already_matched > 0) {
    std::printf("(%zu of the pairs were already matched in the database)\n",
                summary.num_already_matched);
  }
  std::printf("pairs written to %s\n", summary.pairs_path.c_str());
  return 0;
}

}  // namespace colmap_gcn
