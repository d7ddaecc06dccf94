#include "pairing/gcn_pair_generator.h"

#include <algorithm>
#include <unordered_set>

#include "gcn/gcn_inference.h"
#include "gcn/query_enclosing_subgraph.h"
#include "util/error.h"
#include "util/option_check.h"
#include "util/timer.h"

namespace colmap_gcn {

void GcnPairingOptions::Check() const {
  CHECK_OPTION_GE(k1, 1);
  CHECK_OPTION_GE(k2, 0);
  CHECK_OPTION_GE(u, 0);
  CHECK_OPTION_RANGE(threshold, 0.0, 1.0);
  CHECK_OPTION_GE(min_pairs_per_image, 0);
  CHECK_OPTION_GE(block_size, 1);
  CHECK_OPTION_NUM_THREADS(num_threads);
}

GcnPairingOptions EveryCandidate(GcnPairingOptions options) {
  options.threshold = 0;
  options.min_pairs_per_image = 0;
  return options;
}

GcnPairingOptions GcnPairingOptionsFromModel(const GcnModel& model) {
  GcnPairingOptions options;
  options.k1 = model.info.test_k1;
  options.k2 = model.info.test_k2;
  options.u = model.info.test_u;
  options.threshold = model.info.threshold;
  return options;
}

GcnPairGenerator::GcnPairGenerator(const GcnPairingOptions& options,
                                   const std::vector<image_t>& image_ids,
                                   const EmbeddingMatrix& embeddings,
                                   const GcnModel& model)
    : options_(options) {
  options_.Check();
  const int n = static_cast<int>(image_ids.size());
  if (embeddings.rows() != n) {
    ThrowError("GCN pairing got ",
               n,
               " image ids but ",
               embeddings.rows(),
               " embeddings");
  }
  model.CheckEmbeddingDimension(static_cast<int>(embeddings.cols()));
  {
    std::unordered_set<image_t> unique(image_ids.begin(), image_ids.end());
    if (static_cast<int>(unique.size()) != n) {
      ThrowError("GCN pairing got duplicate image ids");
    }
  }
  stats_.num_images = n;
  if (n < 2) return;

  const QesOptions qes =
      CapQesOptions(QesOptions{options_.k1, options_.k2, options_.u}, n);
  Timer timer;
  const KnnGraph knn = ComputeKnnForQes(embeddings, qes, options_.num_threads);
  stats_.knn_seconds = timer.ElapsedSeconds();
  timer.Restart();
  const std::vector<std::vector<float>> scores =
      ScoreAllQueries(model, embeddings, knn, qes, options_.num_threads);
  stats_.gcn_seconds = timer.ElapsedSeconds();

  // Unordered candidates with the max score of both directions.
  struct Candidate {
    uint64_t key;  // (row1 << 32) | row2, row1 < row2
    float score;
  };
  std::vector<Candidate> candidates;
  candidates.reserve(static_cast<size_t>(n) * qes.k1);
  for (int q = 0; q < n; ++q) {
    for (size_t i = 0; i < scores[q].size(); ++i) {
      const int other = knn.indices(q, static_cast<int>(i));
      const uint64_t a = static_cast<uint64_t>(std::min(q, other));
      const uint64_t b = static_cast<uint64_t>(std::max(q, other));
      candidates.push_back({(a << 32) | b, scores[q][i]});
    }
  }
  std::sort(candidates.begin(),
            candidates.end(),
            [](const Candidate& x, const Candidate& y) {
              return x.key != y.key ? x.key < y.key : x.score > y.score;
            });
  size_t unique_end = 0;
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (unique_end == 0 ||
        candidates[unique_end - 1].key != candidates[i].key) {
      candidates[unique_end++] = candidates[i];
    }
  }
  candidates.resize(unique_end);
  stats_.num_candidates = static_cast<int>(candidates.size());

  const float threshold = static_cast<float>(options_.threshold);
  std::vector<uint8_t> selected(candidates.size(), 0);
  std::vector<int> degree(n, 0);
  for (size_t c = 0; c < candidates.size(); ++c) {
    if (candidates[c].score >= threshold) {
      selected[c] = 1;
      ++degree[candidates[c].key >> 32];
      ++degree[candidates[c].key & 0xffffffffu];
      ++stats_.num_above_threshold;
    }
  }

  // min_pairs_per_image: best-scoring candidates of under-connected images,
  // images in row order, candidates by decreasing score then row.
  if (options_.min_pairs_per_image > 0) {
    std::vector<std::vector<int>> incident(n);
    for (size_t c = 0; c < candidates.size(); ++c) {
      incident[candidates[c].key >> 32].push_back(static_cast<int>(c));
      incident[candidates[c].key & 0xffffffffu].push_back(static_cast<int>(c));
    }
    for (int i = 0; i < n; ++i) {
      if (degree[i] >= options_.min_pairs_per_image) continue;
      std::vector<int>& list = incident[i];
      std::stable_sort(list.begin(), list.end(), [&](int x, int y) {
        return candidates[x].score > candidates[y].score;
      });
      for (int c : list) {
        if (degree[i] >= options_.min_pairs_per_image) break;
        if (selected[c]) continue;
        selected[c] = 1;
        ++degree[candidates[c].key >> 32];
        ++degree[candidates[c].key & 0xffffffffu];
        ++stats_.num_fallback;
      }
    }
  }

  for (size_t c = 0; c < candidates.size(); ++c) {
    if (!selected[c]) continue;
    ScoredImagePair pair;
    pair.image_id1 = image_ids[candidates[c].key >> 32];
    pair.image_id2 = image_ids[candidates[c].key & 0xffffffffu];
    pair.score = candidates[c].score;
    pair.above_threshold = candidates[c].score >= threshold;
    pairs_.push_back(pair);
  }
}

void GcnPairGenerator::Reset() { pair_idx_ = 0; }

bool GcnPairGenerator::HasFinished() const {
  return pair_idx_ >= pairs_.size();
}

std::vector<ImagePair> GcnPairGenerator::Next() {
  std::vector<ImagePair> block;
  const size_t end = std::min(
      pairs_.size(), pair_idx_ + static_cast<size_t>(options_.block_size));
  for (; pair_idx_ < end; ++pair_idx_) {
    block.emplace_back(pairs_[pair_idx_].image_id1,
                       pairs_[pair_idx_].image_id2);
  }
  return block;
}

std::vector<float> GcnPairGenerator::Scores() const {
  std::vector<float> scores;
  scores.reserve(pairs_.size());
  for (const ScoredImagePair& pair : pairs_) scores.push_back(pair.score);
  return scores;
}

}  // namespace colmap_gcn
