#include "evaluation/pair_labels.h"

#include <algorithm>

#include "evaluation/common_tracks.h"
#include "evaluation/ground_truth.h"
#include "scene/reconstruction.h"
#include "util/error.h"

namespace colmap_gcn {

PairLabels ComputeGroundTruthCameraLabels(const ColmapRunner& colmap,
                                          const std::string& database_path,
                                          const std::string& gt_model_path,
                                          const std::string& work_dir) {
  Reconstruction ground_truth;
  ground_truth.Read(gt_model_path);
  const Reconstruction triangulated =
      TriangulateOnGroundTruth(colmap, ground_truth, database_path, work_dir);
  std::vector<std::string> names;
  for (const auto& [image_id, image] : ground_truth.images) {
    names.push_back(image.name);
  }
  std::sort(names.begin(), names.end());
  return LabelsFromReconstruction(
      triangulated, names, "GT-camera triangulation (" + gt_model_path + ")");
}

TopKRetrievalScores ScoreTopKRetrieval(
    const KnnGraph& graph,
    const std::vector<std::string>& image_names,
    int k,
    const PairLabels& labels,
    const PairLabelOptions& options) {
  THROW_CHECK(static_cast<size_t>(graph.NumImages()) == image_names.size());
  TopKRetrievalScores scores;
  scores.k = std::min(k, graph.K());
  size_t num_with_partner = 0;
  size_t num_hit = 0;
  for (int q = 0; q < graph.NumImages(); ++q) {
    const std::string& query = image_names[q];
    if (!labels.HasImage(query)) continue;
    size_t num_matchable = 0;
    for (const std::string& other : image_names) {
      if (other != query && labels.HasImage(other) &&
          labels.IsMatchable(query, other, options)) {
        ++num_matchable;
      }
    }
    size_t true_positives = 0;
    for (int n = 0; n < scores.k; ++n) {
      const int j = graph.indices(q, n);
      if (j < 0) continue;
      if (labels.HasImage(image_names[j]) &&
          labels.IsMatchable(query, image_names[j], options)) {
        ++true_positives;
      }
    }
    ++scores.num_queries;
    scores.num_true_positives += true_positives;
    if (scores.k > 0) {
      scores.mean_precision += static_cast<double>(true_positives) / scores.k;
    }
    if (num_matchable > 0) {
      ++num_with_partner;
      num_hit += true_positives > 0;
      scores.mean_recall += static_cast<double>(true_positives) / num_matchable;
    }
  }
  if (scores.num_queries > 0) scores.mean_precision /= scores.num_queries;
  if (num_with_partner > 0) {
    scores.mean_recall /= num_with_partner;
    scores.hit_rate = static_cast<double>(num_hit) / num_with_partner;
  }
  return scores;
}

}  // namespace colmap_gcn
