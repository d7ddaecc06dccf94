#pragma once

#include <string>
#include <vector>

#include "controllers/colmap_runner.h"
#include "evaluation/labels.h"
#include "retrieval/knn.h"

namespace colmap_gcn {

// Ground-truth pair labels of a real scene with GT cameras: the database's
// verified matches (run feature_extractor + exhaustive_matcher first) are
// triangulated on the fixed GT poses and intrinsics (TriangulateOnGroundTruth,
// in work_dir) and every pair gets its common-track ratio
// CT_ij = |P_i n P_j| / min(|P_i|, |P_j|) (LabelsFromReconstruction).
// A pair is matchable when CT_ij >= PairLabelOptions::min_common_track_ratio
// (tau = 0.15 by default). gt_model_path is a COLMAP model (text or binary)
// whose image names are the database's.
PairLabels ComputeGroundTruthCameraLabels(const ColmapRunner& colmap,
                                          const std::string& database_path,
                                          const std::string& gt_model_path,
                                          const std::string& work_dir);

// Retrieval quality of the top-k rows of a kNN graph, per query as in the
// paper's precision/recall at a fixed retrieval number.
struct TopKRetrievalScores {
  int k = 0;                      // neighbours used (capped by the graph)
  size_t num_queries = 0;         // labelled query images
  double mean_precision = 0;      // mean over queries of TP_q / k
  double mean_recall = 0;         // mean over queries with a matchable partner
                                  // of TP_q / |matchable partners of q|
  double hit_rate = 0;            // queries with >= 1 matchable image in top-k,
                                  // among queries that have one
  size_t num_true_positives = 0;  // summed over queries (directed)
};

// image_names[i] names row i of the graph. Unlabelled queries or neighbours
// are skipped.
TopKRetrievalScores ScoreTopKRetrieval(
    const KnnGraph& graph,
    const std::vector<std::string>& image_names,
    int k,
    const PairLabels& labels,
    const PairLabelOptions& options);

}  // namespace colmap_gcn
