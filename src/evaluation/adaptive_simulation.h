#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "controllers/gcn_matching.h"
#include "evaluation/labels.h"
#include "pairing/pairing.h"
#include "scene/database.h"
#include "scene/two_view_geometry_store.h"
#include "verification/pair_verification.h"

namespace colmap_gcn {

// The verification of every pair of an exhaustively matched database, to
// replay pair generators that use verification without running COLMAP:
// "matching" a pair is looking up its two_view_geometries row (no row: not
// verified, 0 inliers).
class VerificationTable {
 public:
  explicit VerificationTable(const Database& database);

  PairVerification Lookup(image_t image_id1, image_t image_id2) const;
  const std::string& Name(image_t image_id) const;
  const std::vector<DatabaseImage>& Images() const { return images_; }
  // Rows of two_view_geometries (0: the database was never matched).
  size_t NumGeometries() const { return geometries_.size(); }
  // A merged collection ("<scene>__<name>" images, collection.h).
  bool IsCollection() const { return is_collection_; }
  // The pairs COLMAP verified with at least strong_cut inliers (image-id
  // order, smaller id first; sorted): everything a loop that counts strong
  // verifications as positives can learn as one.
  std::vector<ImagePair> StrongPairs(int strong_cut) const;
  // Replaces every row by the loop's own deterministic verification of that
  // pair (verification/pair_verification.h) from the database's features,
  // so that a replay sees what the loop run by gcn_matcher decides on.
  void Reverify(const TwoViewGeometryStore& database,
                const ExactVerificationOptions& options);

 private:
  std::vector<DatabaseImage> images_;
  bool is_collection_ = false;
  std::unordered_map<image_t, size_t> image_index_;
  std::unordered_map<image_pair_t, TwoViewGeometryInfo> geometries_;
};

// What a pair set finds, at a strong-verification cut.
struct PairSetQuality {
  size_t num_pairs = 0;      // TAM
  size_t num_verified = 0;   // UM (COLMAP's rule, 15 inliers)
  size_t num_strong = 0;     // verified with >= strong_cut inliers
  size_t num_matchable = 0;  // labelled matchable pairs (0: no labels)
  size_t num_matchable_found = 0;
  size_t num_cross_scene = 0;  // pairs across a collection's scenes
  size_t num_images_with_strong = 0;
  // Images of the largest model the strong pairs can grow: from the
  // strongest pair, an image joins once two of its strong partners are in
  // (GrowthClusters); fewer than the images with a strong pair foretells
  // COLMAP's mapper splitting the scene.
  size_t num_images_grown = 0;
  double Recall() const {
    return num_matchable == 0 ? 0.0
                              : static_cast<double>(num_matchable_found) /
                                    static_cast<double>(num_matchable);
  }
};

// labels may be null (recall then 0, num_matchable 0).
PairSetQuality EvaluatePairSet(const std::vector<ImagePair>& pairs,
                               const VerificationTable& table,
                               const PairLabels* labels,
                               int strong_cut);

// One round of a replayed run: the round's block and the set so far.
struct SimulatedRound {
  size_t num_pairs = 0;
  PairSetQuality total;
};

// Runs `generator` (Reset, then Next / Observe until HasFinished) against
// the table; the attempted pairs in yield order go to *pairs. strong_cut
// is the cut the per-round totals are evaluated at.
std::vector<SimulatedRound> SimulatePairGenerator(
    PairGenerator* generator,
    const VerificationTable& table,
    const PairLabels* labels,
    int strong_cut,
    std::vector<ImagePair>* pairs);

// What `colmap gcn_adaptive_simulator` replays: a generator that uses
// verification (matching.pairing adaptive or graphmatch) on an exhaustively
// matched database, which is only read.
struct AdaptiveSimulationOptions {
  // An exhaustively matched COLMAP database.
  std::string database_path;
  // labels.csv for the recall of labelled matchable pairs; empty: none.
  std::string labels_path = "";
  // Also evaluate the single-shot GCN, its top-TAM scores, kNN at equal
  // TAM, graphmatch and exhaustive matching at the same strong cut.
  bool compare = true;
  // Replay on the loop's deterministic verification of every matched pair
  // (as gcn_matcher's loop decides); false: on COLMAP's rows as stored.
  bool exact_verification = true;
  GcnMatchingOptions matching;
};

// One line of the simulation's tables: a pair set and what it finds.
struct NamedPairSetQuality {
  std::string name;
  PairSetQuality quality;
};

struct AdaptiveSimulationReport {
  size_t num_images = 0;
  // The generator's strong-verification cut (1 for graphmatch).
  int strong_cut = 1;
  // "round r (+n)": the pairs attempted up to and including each round.
  std::vector<NamedPairSetQuality> rounds;
  // The replayed generator first, then the baselines (empty without
  // options.compare).
  std::vector<NamedPairSetQuality> comparisons;
};

// Replays options.matching's generator against the database's
// verifications; throws Error when the database was never matched or the
// generator does not use verification. Writes no embedding cache.
AdaptiveSimulationReport RunAdaptiveSimulation(
    const AdaptiveSimulationOptions& options);

}  // namespace colmap_gcn
