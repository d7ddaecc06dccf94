#include "exe/gcn_adaptive_simulator.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <unordered_set>

#include "controllers/adaptive_pairing.h"
#include "controllers/gcn_matching.h"
#include "evaluation/adaptive_simulation.h"
#include "exe/gcn_matcher.h"
#include "scene/database_copy.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_manager.h"

namespace colmap_gcn {
namespace {

void PrintQualityHeader() {
  std::printf("%-22s %7s %7s %7s %7s %8s %7s %9s\n",
              "method",
              "TAM",
              "UM",
              "strong",
              "found",
              "recall",
              "cross",
              "img_strong");
}

void PrintQuality(const std::string& method, const PairSetQuality& quality) {
  std::printf("%-22s %7zu %7zu %7zu %7zu %8.3f %7zu %9zu\n",
              method.c_str(),
              quality.num_pairs,
              quality.num_verified,
              quality.num_strong,
              quality.num_matchable_found,
              quality.Recall(),
              quality.num_cross_scene,
              quality.num_images_with_strong);
}

// The first `count` distinct pairs of `candidates` in the given order.
std::vector<ImagePair> FirstPairs(const std::vector<PairCandidate>& candidates,
                                  size_t count) {
  std::vector<ImagePair> pairs;
  std::unordered_set<image_pair_t> seen;
  for (const PairCandidate& candidate : candidates) {
    if (pairs.size() >= count) break;
    if (candidate.image_id1 == candidate.image_id2) continue;
    if (seen.insert(ImagePairToPairId(candidate.image_id1, candidate.image_id2))
            .second) {
      pairs.emplace_back(candidate.image_id1, candidate.image_id2);
    }
  }
  return pairs;
}

}  // namespace

int RunGcnAdaptiveSimulator(int argc, char** argv) {
  std::string database_path;
  std::string labels_path;
  bool compare = true;
  GcnMatchingOptions options;
  options.pairing = "adaptive";
  OptionManager manager(
      "gcn_adaptive_simulator",
      "Replays --GcnMatching.pairing adaptive or graphmatch on an "
      "exhaustively matched database without running COLMAP (matching a "
      "pair = reading its two_view_geometries row) and prints every round, "
      "then the same number of pairs chosen by the single-shot GCN and by "
      "kNN. The database is only read.");
  manager.AddRequiredOption("database_path",
                            &database_path,
                            "an exhaustively matched COLMAP database");
  manager.AddDefaultOption("labels_path",
                           &labels_path,
                           "labels.csv for the recall of labelled matchable "
                           "pairs (optional)");
  manager.AddDefaultOption(
      "compare",
      &compare,
      "also evaluate gcn, top-TAM GCN scores, kNN at equal TAM, graphmatch");
  AddGcnMatchingOptions(&manager, &options);
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] { options.Check(); });
  // Checked before the embedding: the generators that use verification.
  if (options.pairing != "adaptive" && options.pairing != "graphmatch") {
    ThrowError("--GcnMatching.pairing ",
               options.pairing,
               " does not use verification; simulate adaptive or graphmatch");
  }
  if (!labels_path.empty() && !ExistsFile(labels_path)) {
    ThrowError("--labels_path ", labels_path, " does not exist");
  }
  // Nothing is written beside the database.
  options.generators.Get<AdaptiveGcnPairingOptions>("adaptive")
      .gcn.use_vlad_cache = false;
  options.generators.Get<AdaptiveGcnPairingOptions>("adaptive")
      .knn.descriptors.use_cache = false;
  options.generators.Get<GcnModelPairingOptions>("gcn").use_vlad_cache = false;
  options.generators.Get<GraphMatchPairingOptions>("graphmatch")
      .knn.descriptors.use_cache = false;
  options.generators.Get<KnnPairingOptions>("knn").descriptors.use_cache =
      false;

  RecoverHotJournal(database_path);
  const Database database(database_path);
  const VerificationTable table(database);
  // Without verifications every replayed pair would count as failed and the
  // table would be all zeros.
  if (table.NumGeometries() == 0) {
    ThrowError("database ",
               database_path,
               " was never matched (its two_view_geometries table is empty); "
               "gcn_adaptive_simulator replays verification from it: run "
               "colmap exhaustive_matcher on it first");
  }
  std::unique_ptr<PairLabels> labels;
  if (!labels_path.empty()) {
    labels = std::make_unique<PairLabels>(PairLabels::Read(labels_path));
  }
  std::unique_ptr<PairGenerator> generator =
      CreatePairGenerator(options, database);
  if (!generator->UsesVerification()) {
    ThrowError("--GcnMatching.pairing ",
               options.pairing,
               " does not use verification; simulate adaptive or graphmatch");
  }
  std::vector<ImagePair> pairs;
  const std::vector<SimulatedRound> rounds =
      SimulatePairGenerator(generator.get(), table, labels.get(), 1, &pairs);
  const auto* adaptive = dynamic_cast<AdaptivePairGenerator*>(generator.get());
  const int cut = adaptive != nullptr ? adaptive->StrongCut() : 1;

  std::printf("%s on %s (%zu images), strong cut %d inliers\n",
              options.pairing.c_str(),
              database_path.c_str(),
              table.Images().size(),
              cut);
  std::printf("%-5s %7s %s\n", "round", "pairs", "(totals so far)");
  PrintQualityHeader();
  size_t end = 0;
  for (size_t r = 0; r < rounds.size(); ++r) {
    end += rounds[r].num_pairs;
    const std::vector<ImagePair> prefix(pairs.begin(), pairs.begin() + end);
    PrintQuality("round " + std::to_string(r + 1) + " (+" +
                     std::to_string(rounds[r].num_pairs) + ")",
                 EvaluatePairSet(prefix, table, labels.get(), cut));
  }
  const PairSetQuality final_quality =
      EvaluatePairSet(pairs, table, labels.get(), cut);
  if (!compare) return 0;

  std::printf("\nat the same strong cut (%d inliers):\n", cut);
  PrintQualityHeader();
  PrintQuality(options.pairing, final_quality);
  std::vector<image_t> image_ids;
  std::vector<PairCandidate> gcn = GcnModelCandidates(
      options.generators.Get<AdaptiveGcnPairingOptions>("adaptive").gcn,
      database,
      &image_ids);
  std::stable_sort(gcn.begin(),
                   gcn.end(),
                   [](const PairCandidate& a, const PairCandidate& b) {
                     return a.score > b.score;
                   });
  PrintQuality(
      "gcn top-TAM scores",
      EvaluatePairSet(
          FirstPairs(gcn, final_quality.num_pairs), table, labels.get(), cut));
  {
    GcnMatchingOptions single = options;
    single.pairing = "gcn";
    PrintQuality(
        "gcn (model threshold)",
        EvaluatePairSet(CreatePairGenerator(single, database)->AllPairs(),
                        table,
                        labels.get(),
                        cut));
  }
  {
    // kNN at equal TAM: every image's nearest neighbour, then every
    // image's second, ... (by similarity within a rank), cut at TAM.
    const KnnPairingOptions& knn_options =
        options.generators.Get<GraphMatchPairingOptions>("graphmatch").knn;
    const std::vector<PairCandidate> knn =
        SimilarityCandidates(knn_options, database, &image_ids);
    const size_t n = image_ids.size();
    const size_t k = n == 0 ? 0 : knn.size() / n;
    std::vector<PairCandidate> by_rank;
    for (size_t rank = 0; rank < k; ++rank) {
      std::vector<PairCandidate> level;
      for (size_t i = 0; i < n; ++i) level.push_back(knn[i * k + rank]);
      std::stable_sort(level.begin(),
                       level.end(),
                       [](const PairCandidate& a, const PairCandidate& b) {
                         return a.score > b.score;
                       });
      by_rank.insert(by_rank.end(), level.begin(), level.end());
    }
    PrintQuality("knn at equal TAM",
                 EvaluatePairSet(FirstPairs(by_rank, final_quality.num_pairs),
                                 table,
                                 labels.get(),
                                 cut));
  }
  if (options.pairing != "graphmatch") {
    GcnMatchingOptions graphmatch = options;
    graphmatch.pairing = "graphmatch";
    std::unique_ptr<PairGenerator> baseline =
        CreatePairGenerator(graphmatch, database);
    std::vector<ImagePair> baseline_pairs;
    SimulatePairGenerator(
        baseline.get(), table, labels.get(), cut, &baseline_pairs);
    PrintQuality("graphmatch",
                 EvaluatePairSet(baseline_pairs, table, labels.get(), cut));
  }
  {
    std::vector<ImagePair> all;
    for (size_t i = 0; i < table.Images().size(); ++i) {
      for (size_t j = i + 1; j < table.Images().size(); ++j) {
        all.emplace_back(table.Images()[i].image_id,
                         table.Images()[j].image_id);
      }
    }
    PrintQuality("exhaustive", EvaluatePairSet(all, table, labels.get(), cut));
  }
  // The ceiling of a loop that learns from strong verifications only: the
  // labelled matchable pairs among them.
  PrintQuality(
      "exhaustive, strong only",
      EvaluatePairSet(table.StrongPairs(cut), table, labels.get(), cut));
  return 0;
}

}  // namespace colmap_gcn
