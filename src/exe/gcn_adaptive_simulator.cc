#include "exe/gcn_adaptive_simulator.h"

#include <cstdio>

#include "controllers/gcn_matching.h"
#include "evaluation/adaptive_simulation.h"
#include "exe/gcn_matcher.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_manager.h"

namespace colmap_gcn {
namespace {

void PrintQualityHeader() {
  std::printf("%-22s %7s %7s %7s %7s %8s %7s %9s %6s\n",
              "method",
              "TAM",
              "UM",
              "strong",
              "found",
              "recall",
              "cross",
              "img_strong",
              "grown");
}

void PrintQuality(const NamedPairSetQuality& line) {
  const PairSetQuality& quality = line.quality;
  std::printf("%-22s %7zu %7zu %7zu %7zu %8.3f %7zu %9zu %6zu\n",
              line.name.c_str(),
              quality.num_pairs,
              quality.num_verified,
              quality.num_strong,
              quality.num_matchable_found,
              quality.Recall(),
              quality.num_cross_scene,
              quality.num_images_with_strong,
              quality.num_images_grown);
}

}  // namespace

int RunGcnAdaptiveSimulator(int argc, char** argv) {
  AdaptiveSimulationOptions options;
  options.matching.pairing = "adaptive";
  OptionManager manager(
      "gcn_adaptive_simulator",
      "Replays --GcnMatching.pairing adaptive or graphmatch on an "
      "exhaustively matched database without running COLMAP (matching a "
      "pair = verifying its features as the loop does, or reading its "
      "two_view_geometries row) and prints every round, "
      "then the same number of pairs chosen by the single-shot GCN and by "
      "kNN. The database is only read.");
  manager.AddRequiredOption("database_path",
                            &options.database_path,
                            "an exhaustively matched COLMAP database");
  manager.AddDefaultOption("labels_path",
                           &options.labels_path,
                           "labels.csv for the recall of labelled matchable "
                           "pairs (optional)");
  manager.AddDefaultOption(
      "compare",
      &options.compare,
      "also evaluate gcn, top-TAM GCN scores, kNN at equal TAM, graphmatch");
  manager.AddDefaultOption(
      "exact_verification",
      &options.exact_verification,
      "replay on the loop's own deterministic verification of each matched "
      "pair, as gcn_matcher decides (0: on COLMAP's stored rows)");
  AddGcnMatchingOptions(&manager, &options.matching);
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] { options.matching.Check(); });
  // Checked before the embedding: the generators that use verification.
  const std::string& pairing = options.matching.pairing;
  if (pairing != "adaptive" && pairing != "adaptive_recall" &&
      pairing != "graphmatch") {
    ThrowError("--GcnMatching.pairing ",
               pairing,
               " does not use verification; simulate adaptive or graphmatch");
  }
  if (!options.labels_path.empty() && !ExistsFile(options.labels_path)) {
    ThrowError("--labels_path ", options.labels_path, " does not exist");
  }

  const AdaptiveSimulationReport report = RunAdaptiveSimulation(options);

  std::printf("%s on %s (%zu images), strong cut %d inliers\n",
              pairing.c_str(),
              options.database_path.c_str(),
              report.num_images,
              report.strong_cut);
  std::printf("%-5s %7s %s\n", "round", "pairs", "(totals so far)");
  PrintQualityHeader();
  for (const NamedPairSetQuality& round : report.rounds) PrintQuality(round);
  if (report.comparisons.empty()) return 0;
  std::printf("\nat the same strong cut (%d inliers):\n", report.strong_cut);
  PrintQualityHeader();
  for (const NamedPairSetQuality& line : report.comparisons) {
    PrintQuality(line);
  }
  return 0;
}

}  // namespace colmap_gcn
