#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "controllers/adaptive_calibration.h"
#include "pairing/gcn_model_pairing.h"
#include "pairing/knn_pairing.h"
#include "pairing/pair_generator_spec.h"
#include "pairing/pairing.h"
#include "util/logging.h"
#include "util/timer.h"
#include "util/types.h"

namespace colmap_gcn {

// Pair selection with COLMAP's verification in the loop (docs/adaptive.md):
// candidates with a prior score (the GCN's, or embedding similarity), matched
// in rounds; after each round the collection's own cut between accidental and
// real ("strong") verifications is learned from the inlier counts, the prior
// is calibrated to P(strong) on the pairs matched so far, and the next round
// takes the most probable candidates while that probability stays above
// min_pair_yield.
//
// When to stop (AdaptiveStopRule):
// - kEnough (adaptive's default): a strong pair must also hold at least
//   relative_strength of the inliers of the best verified pair of the
//   weaker of its two images (like the labels' common-track ratio, so weak
//   overlaps in a collection where almost every pair verifies are not
//   positives); every image keeps trying its most probable
//   candidates until it has min_strong_partners strong partners or has spent
//   image_patience attempts without one; probe rounds run only while they
//   still connect the collection (more images reach min_strong_partners or
//   strong components merge); a pair whose two images already have
//   max_strong_partners strong partners is not asked for, which is what
//   ends the rounds on a dense capture where almost every pair verifies;
//   before it finishes, every strong component keeps trying to reach
//   another one for component_patience attempts.
// - kRecall (adaptive_recall, graphmatch): the rule before kEnough: probe
//   rounds while the last round's strong fraction reached min_pair_yield,
//   then the connectivity attempts of isolated_retries.
enum class AdaptiveStopRule { kEnough, kRecall };

struct AdaptivePairingOptions {
  // Round 1: every image's best candidates by prior score.
  int initial_per_image = 3;

  // Round 1 also attempts this fraction of its size in lower-ranked
  // candidates, one drawn (with seed) from each of as many equal score
  // strata, so that the calibration sees the whole score range ...
  double exploration_fraction = 0.1;
  // ... but at most this many: the calibration needs a sample of the score
  // range, not one that grows with the collection, and in a photo
  // collection of many places most lower-ranked candidates are pairs of
  // two places. 0: no cap.
  int max_exploration_pairs = 50;
  int seed = 0;

  // Pairs per later round; -1: the number of images, at least 50.
  int round_size = -1;

  // Later rounds attempt the candidates whose calibrated probability of a
  // strong verification is at least this. When none reaches it but the
  // last round's observed strong fraction did, a probe round takes the
  // most probable candidates anyway (the calibration only extrapolates
  // below the scores matched so far); matching stops once no candidate
  // reaches it and the last round's observed fraction fell below it
  // (after the connectivity attempts below).
  double min_pair_yield = 0.5;

  // Hard budget of attempted pairs; 0: none.
  int max_num_pairs = 0;

  // The strong-verification cut, in inliers: the Otsu split of
  // log(inliers) over the verified pairs seen so far when that split is
  // bimodal (between-class share of the variance >= 0.75), its lower class
  // looks accidental (median <= 30 inliers, twice COLMAP's default
  // min_num_inliers) and at least 20 pairs verified, clamped to
  // [min_strong_inliers, max_strong_inliers]; otherwise min_strong_inliers.
  int min_strong_inliers = 30;
  int max_strong_inliers = 150;

  // Propagation: candidates are classed by how many strong paths of two
  // edges they close (common strong neighbours: 0, 1, 2-3, 4-7, >= 8);
  // once at least this many matched pairs fall in a class, its candidates
  // get a log-odds offset on the score's calibrated probability, fitted so
  // that the class's matched pairs are predicted as often strong as they
  // were; a class with fewer samples gets no offset.
  int min_propagation_samples = 10;

  // Connectivity: once no candidate reaches min_pair_yield, every image
  // with candidates but no attempted pair gets its most probable one, and
  // every image without a strong pair up to this many more attempts.
  int isolated_retries = 2;

  // kEnough / kRecall (see AdaptiveStopRule); chosen by the pairing's name
  // (adaptive / adaptive_recall), not a flag.
  AdaptiveStopRule stop_rule = AdaptiveStopRule::kEnough;

  // kEnough: a verified pair is strong only with at least this share of
  // the inliers of the best verified pair of the weaker of its images
  // (IsRelativelyStrong).
  double relative_strength = 0.05;

  // kEnough: strong partners every image keeps trying to reach ...
  int min_strong_partners = 3;

  // ... while it has spent fewer than this many attempts that did not
  // verify strongly (its candidates tried in order of probability).
  int image_patience = 5;

  // kEnough: an image with this many strong partners has enough for the
  // mapper (hloc's SfM pipelines triangulate from each image's 20 most
  // covisible images); later rounds skip candidates whose two images both
  // have it, so a dense capture where almost every pair verifies strongly
  // stops short of exhaustive's budget. 0: no cap.
  int max_strong_partners = 20;

  // kEnough: once nothing else is asked for, every model the strong pairs
  // can grow (GrowthClusters: from the strongest pair, an image joins once
  // two of its strong partners are in) of three or more images tries, one
  // a round, its most probable candidates that lead to another such model,
  // until they grow into one or it has spent this many attempts still
  // leading out of it. A block of photos whose images have all found their
  // partners inside it is otherwise a model of its own. 0: none.
  int component_patience = 5;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// A candidate pair and its prior score (higher: more likely to match).
struct PairCandidate {
  image_t image_id1 = kInvalidImageId;
  image_t image_id2 = kInvalidImageId;
  float score = 0.f;
  // Next to each other in name order (consecutive photos of a capture).
  // The loop learns from its own verifications whether that order means
  // overlap (a walk, a video) or nothing (web photos): such pairs get a
  // log-odds offset of their own once enough of them were matched.
  bool consecutive = false;
};

// One round as logged.
struct AdaptiveRound {
  int round = 0;               // 1-based
  size_t num_pairs = 0;        // attempted in this round
  double expected_yield = -1;  // mean calibrated P(strong); -1: round 1
  bool probe = false;          // taken below min_pair_yield to probe
  bool connectivity = false;   // the connectivity attempts
  bool bridging = false;       // kEnough: attempts between strong components
  size_t num_guarantee = 0;    // kEnough: pairs for images below
                               // min_strong_partners
  size_t num_connected = 0;    // kEnough, after it: images with
                               // min_strong_partners strong partners
  size_t num_components = 0;   // kEnough, after it: strong components
  size_t num_verified = 0;     // of this round's pairs
  size_t num_strong = 0;       // of this round's pairs, at the cut below
  int strong_cut = 0;          // inliers, learned after this round
  size_t total_attempted = 0;
  size_t total_strong = 0;  // all attempted pairs, at the cut above
  double seconds = 0;       // Next() to Observe(), matching included
};

// The collection's strong-verification cut (see AdaptivePairingOptions).
inline int LearnStrongInlierCut(const std::vector<size_t>& verified_inliers,
                                const AdaptivePairingOptions& options) {
  return LearnStrongInlierCut(
      verified_inliers, options.min_strong_inliers, options.max_strong_inliers);
}

// The sample-calibrate-propagate loop over a fixed candidate list; COLMAP
// independent (tests and gcn_adaptive_simulator drive it with tables of
// verification results). Pairs are handed out once each; the next block
// depends only on the candidates, options and what Observe() got, so a run
// that is fed the same results repeats exactly.
class AdaptivePairGenerator : public PairGenerator {
 public:
  // candidates: unordered pairs of image_ids (duplicates keep the higher
  // score); label names the generator in log lines.
  AdaptivePairGenerator(const AdaptivePairingOptions& options,
                        const std::vector<image_t>& image_ids,
                        const std::vector<PairCandidate>& candidates,
                        const std::string& label = "adaptive");

  void Reset() override;
  bool HasFinished() const override;
  std::vector<ImagePair> Next() override;
  std::vector<float> Scores() const override;
  bool UsesVerification() const override { return true; }
  void Observe(const std::vector<PairVerification>& verifications) override;

  // Pairs a later filter rejects (e.g. a look-alike check): a rejected pair
  // is never strong, so it is no propagation edge and no partner. Set before
  // the first Observe(); empty: none rejected.
  using PairRejection = std::function<bool(image_t, image_t)>;
  void SetPairRejection(PairRejection rejected) {
    rejected_ = std::move(rejected);
  }

  const std::vector<AdaptiveRound>& Rounds() const { return rounds_; }
  int StrongCut() const { return strong_cut_; }
  size_t NumCandidates() const { return candidates_.size(); }
  const AdaptivePairingOptions& Options() const { return options_; }

 private:
  struct Candidate {
    int row1 = 0;
    int row2 = 0;
    float score = 0.f;
    enum class State : uint8_t {
      kUntried,
      kPending,
      kObserved
    } state = State::kUntried;
    bool verified = false;
    size_t num_inliers = 0;
    bool bridge = false;  // yielded by a bridging round
    bool consecutive = false;
  };

  void PrepareNext() const;  // fills next_ (logical constness: a cache)
  std::vector<int> FirstRound() const;
  std::vector<int> LaterRound() const;
  bool IsStrong(const Candidate& candidate) const;
  bool IsStrong(int c) const { return IsStrong(candidates_[c]); }
  size_t Budget() const;
  size_t RoundSize() const;
  // kEnough: the images' most probable candidates while they are below
  // min_strong_partners and within image_patience (not in `taken`).
  std::vector<int> GuaranteeBlock(const std::vector<int>& untried,
                                  const std::vector<uint8_t>& taken,
                                  size_t budget) const;
  // kEnough: one candidate per model the strong pairs can grow, its most
  // probable one leading to another, within component_patience (from the
  // candidates uncapped by max_strong_partners).
  std::vector<int> BridgeBlock(const std::vector<int>& untried,
                               size_t budget) const;
  // kRecall: the connectivity attempts.
  std::vector<int> ConnectivityBlock(const std::vector<int>& untried,
                                     size_t budget) const;
  // kEnough: images with min_strong_partners strong partners, and strong
  // components (isolated images count).
  void Connectivity(size_t* num_connected, size_t* num_components) const;
  void LogRound(const AdaptiveRound& round) const;
  double Probability(int c) const;
  // Strong neighbours the pair's images have in common (the strong paths
  // of length two it closes), and its support class (kSupportClasses).
  int CommonStrongNeighbours(int c) const;
  int SupportClass(int c) const;
  void Refit();
  // Refit's log-odds offsets (support classes, consecutive pairs, strong
  // components), after the calibration.
  void FitOffsets();
  // A candidate's calibrated log-odds with its support and consecutive
  // offsets (Probability adds its component's).
  double OffsetLogit(int c) const;

  const AdaptivePairingOptions options_;
  const std::string label_;
  std::vector<image_t> image_ids_;
  std::unordered_map<image_t, int> rows_;
  std::vector<Candidate> candidates_;
  std::unordered_map<uint64_t, int> candidate_index_;  // (row1<<32)|row2
  std::vector<std::vector<int>> incident_;             // candidates per row

  // Run state.
  std::vector<int> yielded_;  // candidate indices in yield order
  std::vector<AdaptiveRound> rounds_;
  std::vector<std::vector<int>> strong_neighbours_;  // sorted rows
  int strong_cut_ = 0;
  IsotonicCalibration calibration_;  // all observed pairs, by score
  // Log-odds offset per support class (0, 1, 2-3, 4-7, >= 8 common strong
  // neighbours).
  std::vector<double> support_offsets_;
  // Log-odds offset of consecutive pairs, over the support offset.
  double consecutive_offset_ = 0;
  // The strong components after round 1, frozen (row -> label); each
  // one's log-odds offset, over the support and consecutive offsets,
  // fitted on the later rounds' matched pairs inside it (0 with fewer than
  // min_propagation_samples). In a collection of places each place learns
  // its own yield, whatever its scores are next to the others'.
  std::vector<int> first_components_;
  std::vector<double> component_offsets_;  // by label
  std::vector<int> retries_;               // connectivity attempts per row
  std::vector<int> failures_;         // kEnough: attempts not strong, per row
  std::vector<size_t> best_inliers_;  // best verified pair per row
  PairRejection rejected_;
  Timer round_timer_;
  std::unique_ptr<ProgressLogger> progress_;  // from the first round
  mutable bool prepared_ = false;
  mutable std::vector<int> next_;
  mutable double next_yield_ = -1;
  mutable bool next_probe_ = false;
  mutable bool next_connectivity_ = false;
  mutable bool next_bridging_ = false;
  mutable size_t next_guarantee_ = 0;
};

// --GcnMatching.pairing adaptive: the GCN model's candidates (all k1
// neighbours of every image with their GCN scores) through
// AdaptivePairGenerator.
struct AdaptiveGcnPairingOptions {
  AdaptiveGcnPairingOptions();
  // The model's options; k1 defaults to 100 (the paper's test-time k1), not
  // the model's, since the rounds, not a threshold, choose among them.
  GcnModelPairingOptions gcn;
  AdaptivePairingOptions adaptive;
  // Weight of embedding similarity in the prior: with w > 0 the candidates
  // are the union of the GCN's and the similarity kNN's (knn, k = 100),
  // scored (1 - w) * the GCN score's percentile + w * the similarity's
  // percentile in its images' own lists (CombinePriors); 0: the GCN score
  // alone. The GCN's scores alone stop the rounds early: they rank many
  // real pairs low (docs/adaptive.md).
  double similarity_weight = 0.5;
  KnnPairingOptions knn;
  void Check() const;
};

// Two candidate lists combined over their union as (1 - weight_b) * a's
// percentile + weight_b * b's (a pair missing from a list has percentile 0
// there); unordered pairs, sorted by (smaller id, larger id). a's scores
// (the GCN's probabilities) are ranked over the whole list; b's
// (similarities, whose level differs from image to image) within each
// image's own list, the better of the pair's two images counting, as kNN
// retrieval ranks: a photo that looks little like any other still has its
// best partners near the top. Ties share their mean percentile.
std::vector<PairCandidate> CombinePriors(const std::vector<PairCandidate>& a,
                                         const std::vector<PairCandidate>& b,
                                         double weight_b);

// Marks the candidates whose images are next to each other in name order
// and adds those missing with the lowest prior score (0).
void AddConsecutivePairs(const Database& database,
                         std::vector<PairCandidate>* candidates);

// The candidates of the GCN model (threshold 0: every scored 1-hop pair).
std::vector<PairCandidate> GcnModelCandidates(
    const GcnModelPairingOptions& options,
    const Database& database,
    std::vector<image_t>* image_ids);

PairGeneratorSpec<AdaptiveGcnPairingOptions> AdaptivePairGeneratorSpec();
// --GcnMatching.pairing adaptive_recall: the same with the kRecall rule.
PairGeneratorSpec<AdaptiveGcnPairingOptions> AdaptiveRecallPairGeneratorSpec();

// --GcnMatching.pairing graphmatch: a GraphMatch-style baseline (Cui et
// al., 3DV 2017) with no GCN: the k nearest neighbours by embedding
// similarity, that similarity as the prior, then the same rounds,
// propagation and stopping rule as adaptive.
struct GraphMatchPairingOptions {
  GraphMatchPairingOptions();
  KnnPairingOptions knn;  // k defaults to 100, adaptive's k1
  AdaptivePairingOptions adaptive;
  void Check() const;
};

// The kNN candidates with their similarities.
std::vector<PairCandidate> SimilarityCandidates(
    const KnnPairingOptions& options,
    const Database& database,
    std::vector<image_t>* image_ids);

PairGeneratorSpec<GraphMatchPairingOptions> GraphMatchPairGeneratorSpec();

}  // namespace colmap_gcn
