#pragma once

#include <vector>

#include "gcn/gcn_model.h"
#include "pairing/pairing.h"
#include "retrieval/knn.h"
#include "util/types.h"

namespace colmap_gcn {

struct GcnPairingOptions {
  // QES at test time (paper Sec. 4: k1 = 100, k2 = 5, u = 10; u = 5 is the
  // benchmark's setting). All are capped at N - 1 for small collections.
  int k1 = 100;
  int k2 = 5;
  int u = 5;
  // A 1-hop neighbour is retrieved when sigmoid(logit) >= threshold.
  double threshold = 0.5;
  // Every image keeps at least this many pairs: if fewer of its pairs clear
  // the threshold, its best-scoring candidates are added (pairs counted from
  // either side), so no image is cut off from the view graph. 0 disables.
  int min_pairs_per_image = 2;
  // Threads for kNN and GCN; -1 = all cores. Results do not depend on it.
  int num_threads = -1;
  // Pairs per Next() block.
  int block_size = 1225;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// k1, k2, u and threshold recommended by the model file; other fields default.
GcnPairingOptions GcnPairingOptionsFromModel(const GcnModel& model);

// `options` that keep every candidate the GCN scores (every 1-hop pair of
// every QES): threshold 0 and no min_pairs_per_image, for callers that rank
// or cut the scored candidates themselves.
GcnPairingOptions EveryCandidate(GcnPairingOptions options);

struct ScoredImagePair {
  image_t image_id1 = kInvalidImageId;
  image_t image_id2 = kInvalidImageId;
  float score = 0.f;             // max over both directions of sigmoid(logit)
  bool above_threshold = false;  // false: added by min_pairs_per_image
};

struct GcnPairingStats {
  int num_images = 0;
  int num_candidates = 0;  // unordered 1-hop pairs scored
  int num_above_threshold = 0;
  int num_fallback = 0;  // added by min_pairs_per_image
  double knn_seconds = 0;
  double gcn_seconds = 0;
};

// Pairs retrieved by the GCN (paper Sec. 3): kNN graph (exact, k =
// max(k1, k2, u)), a QES per query, GCN scores for its 1-hop neighbours.
// Every unordered pair is yielded once (chosen from either side; its score is
// the max of both directions), ordered by (row of image 1, row of image 2)
// with image 1 the earlier row. All work happens in the constructor.
class GcnPairGenerator : public PairGenerator {
 public:
  using PairOptions = GcnPairingOptions;

  // embeddings.row(i) belongs to image_ids[i]. Throws Error on a model /
  // embedding dimension mismatch or duplicate ids.
  GcnPairGenerator(const GcnPairingOptions& options,
                   const std::vector<image_t>& image_ids,
                   const EmbeddingMatrix& embeddings,
                   const GcnModel& model);

  void Reset() override;
  bool HasFinished() const override;
  std::vector<ImagePair> Next() override;
  std::vector<float> Scores() const override;

  // The selected pairs with their scores, in yield order.
  const std::vector<ScoredImagePair>& ScoredPairs() const { return pairs_; }
  const GcnPairingStats& Stats() const { return stats_; }
  const GcnPairingOptions& Options() const { return options_; }

 private:
  const GcnPairingOptions options_;
  std::vector<ScoredImagePair> pairs_;
  GcnPairingStats stats_;
  size_t pair_idx_ = 0;
};

}  // namespace colmap_gcn
