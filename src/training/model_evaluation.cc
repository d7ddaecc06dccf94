#include "training/model_evaluation.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "evaluation/figures.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

std::string Fixed3(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", value);
  return text;
}

std::string Scores(const PairSetScore& scores) {
  return Fixed3(scores.precision) + " | " + Fixed3(scores.recall) + " | " +
         Fixed3(scores.f_measure);
}

// Mean precision, recall and F of one pair set per scene.
GcnSensitivityPoint MeanScores(
    const std::vector<GcnTrainingScene>& scenes,
    const std::vector<std::vector<std::pair<int, int>>>& pairs,
    const std::string& parameter,
    double value) {
  GcnSensitivityPoint point;
  point.parameter = parameter;
  point.value = value;
  for (size_t s = 0; s < scenes.size(); ++s) {
    const PairSetScore scores = ScorePairSet(pairs[s], scenes[s]);
    point.precision += scores.precision;
    point.recall += scores.recall;
    point.f += scores.f_measure;
    point.pairs_per_image += static_cast<double>(scores.num_pairs) /
                             std::max<int64_t>(1, scenes[s].embeddings.rows());
  }
  const double n = static_cast<double>(std::max<size_t>(1, scenes.size()));
  point.precision /= n;
  point.recall /= n;
  point.f /= n;
  point.pairs_per_image /= n;
  return point;
}

// Candidate pairs by descending score (ties by rows, so the order is
// reproducible).
std::vector<std::pair<int, int>> RankedByScore(
    std::vector<ScoredRowPair> candidates) {
  std::sort(candidates.begin(),
            candidates.end(),
            [](const ScoredRowPair& a, const ScoredRowPair& b) {
              if (a.score != b.score) return a.score > b.score;
              if (a.row1 != b.row1) return a.row1 < b.row1;
              return a.row2 < b.row2;
            });
  std::vector<std::pair<int, int>> ranked;
  for (const auto& candidate : candidates) {
    ranked.emplace_back(candidate.row1, candidate.row2);
  }
  return ranked;
}

std::string PrecisionOrDash(double precision) {
  return precision < 0 ? "—" : Fixed3(precision);
}

}  // namespace

std::vector<GcnTrainingScene> EmbedScenesForModel(
    const GcnModel& model,
    const std::vector<LabelledScene>& scenes,
    const PairLabelOptions& label_options,
    int num_threads,
    const std::string& onnx_path,
    const SceneImageOptions& images,
    const std::string& onnx_flag) {
  if (EmbeddingConfigType(model.embedding) == EmbeddingType::kImported) {
    ThrowError("the model uses imported descriptors (",
               model.embedding.type,
               "); only VLAD and CNN models can embed benchmark scenes");
  }
  ModelEmbeddingOptions options;
  options.embedding.onnx_path = onnx_path;
  options.onnx_flag = onnx_flag;
  options.num_threads = num_threads;
  options.use_vlad_cache = false;
  const ModelEmbedder embedder(model.embedding, options);
  std::vector<GcnTrainingScene> embedded;
  for (const auto& scene : scenes) {
    embedded.push_back(
        MakeTrainingScene(scene, embedder, images, label_options));
    model.CheckEmbeddingDimension(
        static_cast<int>(embedded.back().embeddings.cols()));
  }
  return embedded;
}

double FixedKComparison::KeptFraction() const {
  return num_candidates > 0
             ? static_cast<double>(gcn.num_pairs) / num_candidates
             : 0.0;
}

FixedKComparison CompareWithFixedK(const GcnModel& model,
                                   const GcnTrainingScene& scene,
                                   int max_k,
                                   int num_threads) {
  FixedKComparison result;
  result.scene = scene.name;
  result.num_unrelated_pairs = scene.unrelated_pairs.size();
  result.threshold = model.info.threshold;
  result.num_images = static_cast<int>(scene.embeddings.rows());
  result.is_collection = !scene.part_of_row.empty();
  const std::vector<ScoredRowPair> candidates =
      GcnCandidatePairs(model, scene, num_threads);
  result.num_candidates = candidates.size();
  result.gcn =
      ScorePairSet(PairsAtThreshold(candidates, model.info.threshold), scene);
  const std::vector<uint8_t> matchable = MatchableFlags(candidates, scene);
  std::vector<float> scores;
  std::vector<float> similarities;
  for (const auto& candidate : candidates) {
    scores.push_back(candidate.score);
    similarities.push_back(scene.embeddings.row(candidate.row1)
                               .dot(scene.embeddings.row(candidate.row2)));
  }
  result.gcn_ap = AveragePrecision(scores, matchable);
  result.similarity_ap = AveragePrecision(similarities, matchable);
  const int n = static_cast<int>(scene.embeddings.rows());
  const std::vector<std::pair<int, int>> by_similarity = MostSimilarPairs(
      scene.embeddings, static_cast<size_t>(n) * std::max(n - 1, 0) / 2);
  result.similarity_precision_at_recall =
      BestPrecisionAtRecall(by_similarity, scene, kPrecisionAtRecall);
  result.gcn_precision_at_recall = BestPrecisionAtRecall(
      RankedByScore(candidates), scene, kPrecisionAtRecall);
  result.equal =
      ScorePairSet({by_similarity.begin(),
                    by_similarity.begin() +
                        std::min(by_similarity.size(), result.gcn.num_pairs)},
                   scene);
  result.equal_recall =
      ScorePairSet(ShortestPrefixWithTruePositives(
                       by_similarity, scene, result.gcn.num_true_positives),
                   scene);
  if (n < 2) return result;
  KnnOptions knn_options;
  knn_options.k = std::min(max_k, n - 1);
  knn_options.num_threads = num_threads;
  const KnnGraph graph = ComputeExactKnn(scene.embeddings, knn_options);
  for (int k = 1; k <= graph.K(); ++k) {
    const PairSetScore scores = ScorePairSet(TopKPairs(graph, k), scene);
    if (result.equal_k == 0 && scores.num_pairs >= result.gcn.num_pairs) {
      result.equal_k = k;
      result.top_k_equal = scores;
    }
    if (result.best_k == 0 || scores.f_measure > result.top_k_best.f_measure) {
      result.best_k = k;
      result.top_k_best = scores;
    }
  }
  return result;
}

std::vector<FixedKComparison> CompareWithFixedK(
    const GcnModel& model,
    const std::vector<GcnTrainingScene>& scenes,
    int max_k,
    int num_threads) {
  std::vector<FixedKComparison> comparisons;
  for (const auto& scene : scenes) {
    comparisons.push_back(CompareWithFixedK(model, scene, max_k, num_threads));
  }
  return comparisons;
}

namespace {

// The main table: the GCN at its threshold against fixed-k retrieval, with
// mean F, mean AP and how often the precision target is met.
void FormatOperatingPointTable(const std::vector<FixedKComparison>& comparisons,
                               std::ostringstream* out_ptr) {
  std::ostringstream& out = *out_ptr;
  char line[256];
  out << "GCN at its model's threshold (thr); kept: the fraction of its "
         "candidate pairs (the 1-hop nodes of every QES) the GCN keeps; "
         "kNN= the same number of pairs, most similar first; top-k= the "
         "smallest per-image k with at least as many pairs; best k = the "
         "per-image k with the highest F (chosen with the labels: an upper "
         "bound for any fixed k).\n\n"
      << "AP: average precision of the GCN's candidate pairs ranked by GCN "
         "score and by embedding similarity.\n\n"
      << "| scene | images | thr | candidates | pairs | kept | matchable | "
         "GCN P | R | F | kNN= P | R | F | top-k= k | P | R | F | best k | "
         "P | R | F | AP GCN | AP sim |\n"
      << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
         "---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  double gcn = 0, equal = 0, top_k = 0, best = 0, gcn_ap = 0, sim_ap = 0;
  int gcn_wins = 0;
  int operating_target = 0, reachable_target = 0, similarity_target = 0;
  for (const auto& c : comparisons) {
    std::snprintf(line, sizeof(line), "%.3g", c.threshold);
    out << "| " << c.scene << " | " << c.num_images << " | " << line << " | "
        << c.num_candidates << " | " << c.gcn.num_pairs << " | "
        << Fixed3(c.KeptFraction()) << " | " << c.gcn.num_matchable << " | "
        << Scores(c.gcn) << " | " << Scores(c.equal) << " | " << c.equal_k
        << " | " << Scores(c.top_k_equal) << " | " << c.best_k << " | "
        << Scores(c.top_k_best) << " | " << Fixed3(c.gcn_ap) << " | "
        << Fixed3(c.similarity_ap) << " |\n";
    gcn_ap += c.gcn_ap;
    sim_ap += c.similarity_ap;
    gcn += c.gcn.f_measure;
    equal += c.equal.f_measure;
    top_k += c.top_k_equal.f_measure;
    best += c.top_k_best.f_measure;
    gcn_wins += c.gcn.f_measure >= c.top_k_best.f_measure;
    operating_target += c.gcn.precision >= kTargetPrecision &&
                        c.gcn.recall >= kPrecisionAtRecall;
    reachable_target += c.gcn_precision_at_recall >= kTargetPrecision;
    similarity_target += c.similarity_precision_at_recall >= kTargetPrecision;
  }
  const double n = static_cast<double>(std::max<size_t>(1, comparisons.size()));
  std::snprintf(line,
                sizeof(line),
                "%.3f, kNN= %.3f, top-k= %.3f, best k %.3f",
                gcn / n,
                equal / n,
                top_k / n,
                best / n);
  out << "\nMean F: GCN " << line << "; GCN F >= best-k F on " << gcn_wins
      << " of " << comparisons.size() << " scenes.\n";
  out << "Mean AP: GCN " << Fixed3(gcn_ap / n) << ", similarity "
      << Fixed3(sim_ap / n) << ".\n";
  std::snprintf(line,
                sizeof(line),
                "P >= %.2f at R >= %.1f: the GCN at its threshold on %d of "
                "%zu scenes; reachable by some threshold on the GCN's "
                "ranking on %d, on similarity's on %d.\n",
                kTargetPrecision,
                kPrecisionAtRecall,
                operating_target,
                comparisons.size(),
                reachable_target,
                similarity_target);
  out << line;
}

// Wrong pairs: what folds models on ambiguous scenes. kNN@R is the fewest
// most-similar pairs with the GCN's recall.
void FormatWrongPairsTable(const std::vector<FixedKComparison>& comparisons,
                           std::ostringstream* out_ptr) {
  std::ostringstream& out = *out_ptr;
  out << "\nWrong pairs (labelled pairs whose images share nothing) admitted "
         "by the GCN and by kNN at equal recall (kNN@R: the fewest most "
         "similar pairs with at least the GCN's true positives).\n\n"
      << "| scene | unrelated pairs | GCN pairs | R | wrong | kNN@R pairs "
         "| R | wrong |\n"
      << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
  size_t gcn_wrong = 0, knn_wrong = 0;
  int fewer = 0;
  for (const auto& c : comparisons) {
    out << "| " << c.scene << " | " << c.num_unrelated_pairs << " | "
        << c.gcn.num_pairs << " | " << Fixed3(c.gcn.recall) << " | "
        << c.gcn.num_wrong_pairs << " | " << c.equal_recall.num_pairs << " | "
        << Fixed3(c.equal_recall.recall) << " | "
        << c.equal_recall.num_wrong_pairs << " |\n";
    gcn_wrong += c.gcn.num_wrong_pairs;
    knn_wrong += c.equal_recall.num_wrong_pairs;
    fewer += c.gcn.num_wrong_pairs < c.equal_recall.num_wrong_pairs;
  }
  out << "\nWrong pairs in total: GCN " << gcn_wrong << ", kNN@R " << knn_wrong
      << "; GCN admits fewer on " << fewer << " of " << comparisons.size()
      << " scenes.\n";
}

// Collections of scenes that share nothing: pairs across scenes can only be
// wrong (the unrelated-photo target: <= 1 % at within-scene recall >= 0.9).
void FormatCollectionTable(const std::vector<FixedKComparison>& comparisons,
                           std::ostringstream* out_ptr) {
  std::ostringstream& out = *out_ptr;
  bool any_collection = false;
  for (const auto& c : comparisons) {
    if (!c.is_collection) continue;
    if (!any_collection) {
      out << "\nCollections (pairs across their scenes share nothing): "
             "chosen pairs across scenes, GCN and kNN at equal recall.\n\n"
          << "| collection | images | GCN pairs | R | across scenes | % | "
             "kNN@R pairs | across scenes | % |\n"
          << "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
      any_collection = true;
    }
    auto percent = [](size_t part, size_t whole) {
      char text[32];
      std::snprintf(
          text, sizeof(text), "%.2f", whole > 0 ? 100.0 * part / whole : 0.0);
      return std::string(text);
    };
    out << "| " << c.scene << " | " << c.num_images << " | " << c.gcn.num_pairs
        << " | " << Fixed3(c.gcn.recall) << " | " << c.gcn.num_cross_scene
        << " | " << percent(c.gcn.num_cross_scene, c.gcn.num_pairs) << " | "
        << c.equal_recall.num_pairs << " | " << c.equal_recall.num_cross_scene
        << " | "
        << percent(c.equal_recall.num_cross_scene, c.equal_recall.num_pairs)
        << " |\n";
  }
}

// Whether any threshold could meet the ground-truth target: the best
// precision each ranking reaches at the target recall.
void FormatPrecisionAtRecallTable(
    const std::vector<FixedKComparison>& comparisons,
    std::ostringstream* out_ptr) {
  std::ostringstream& out = *out_ptr;
  char line[32];
  std::snprintf(line, sizeof(line), "%.1f", kPrecisionAtRecall);
  out << "\nBest precision at recall >= " << line
      << " (the threshold chosen with the labels: an upper bound for any "
         "threshold on that ranking; — never reaches that recall): GCN "
         "score over its candidates, similarity over all pairs.\n\n"
      << "| scene | GCN | similarity |\n|---|---:|---:|\n";
  for (const auto& c : comparisons) {
    out << "| " << c.scene << " | "
        << PrecisionOrDash(c.gcn_precision_at_recall) << " | "
        << PrecisionOrDash(c.similarity_precision_at_recall) << " |\n";
  }
}

}  // namespace

std::string FormatFixedKComparison(
    const std::vector<FixedKComparison>& comparisons) {
  std::ostringstream out;
  FormatOperatingPointTable(comparisons, &out);
  FormatWrongPairsTable(comparisons, &out);
  FormatCollectionTable(comparisons, &out);
  FormatPrecisionAtRecallTable(comparisons, &out);
  return out.str();
}

std::vector<EvaluationFold> ReadEvaluationFolds(const std::string& path) {
  std::ifstream file(path);
  if (!file) ThrowError("cannot read the folds file ", path);
  std::vector<EvaluationFold> folds;
  std::set<std::string> seen;
  std::string text;
  for (int number = 1; std::getline(file, text); ++number) {
    const std::string trimmed = StringTrim(text);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    std::istringstream fields(trimmed);
    EvaluationFold fold;
    std::string scenes, extra;
    if (!(fields >> fold.model_path >> scenes) || (fields >> extra)) {
      ThrowError(path,
                 " line ",
                 number,
                 ": expected \"<model path> <scene>[,<scene>...]\"");
    }
    fold.scenes = SplitCommaList(scenes);
    for (const auto& scene : fold.scenes) {
      if (!seen.insert(scene).second) {
        ThrowError(path, " line ", number, ": scene ", scene, " listed twice");
      }
    }
    folds.push_back(fold);
  }
  if (folds.empty()) ThrowError("the folds file ", path, " lists no fold");
  return folds;
}

void GcnSensitivityOptions::Check() const {
  auto positive = [](const std::vector<int>& values) {
    return std::all_of(
        values.begin(), values.end(), [](int v) { return v > 0; });
  };
  CHECK_OPTION(k1_values, positive(k1_values), "be positive");
  CHECK_OPTION(k2_values, positive(k2_values), "be positive");
  CHECK_OPTION(u_values, positive(u_values), "be positive");
  CHECK_OPTION(thresholds,
               std::all_of(thresholds.begin(),
                           thresholds.end(),
                           [](double t) { return t > 0 && t < 1; }),
               "be in (0, 1)");
  CHECK_OPTION_NUM_THREADS(num_threads);
}

std::vector<GcnSensitivityPoint> ComputeGcnSensitivity(
    const GcnModel& model,
    const std::vector<GcnTrainingScene>& scenes,
    const GcnSensitivityOptions& options) {
  options.Check();
  std::vector<GcnSensitivityPoint> points;
  const auto sweep = [&](const std::string& parameter,
                         const std::vector<int>& values,
                         int GcnModelInfo::*field) {
    for (const int value : values) {
      GcnModel varied = model;
      varied.info.*field = value;
      std::vector<std::vector<std::pair<int, int>>> pairs;
      for (const auto& scene : scenes) {
        pairs.push_back(GcnRetrievedPairs(varied, scene, options.num_threads));
      }
      points.push_back(MeanScores(scenes, pairs, parameter, value));
    }
  };
  sweep("k1", options.k1_values, &GcnModelInfo::test_k1);
  sweep("k2", options.k2_values, &GcnModelInfo::test_k2);
  sweep("u", options.u_values, &GcnModelInfo::test_u);
  // The threshold only filters the candidates: score them once.
  std::vector<std::vector<ScoredRowPair>> candidates;
  for (const auto& scene : scenes) {
    candidates.push_back(GcnCandidatePairs(model, scene, options.num_threads));
  }
  for (const double threshold : options.thresholds) {
    std::vector<std::vector<std::pair<int, int>>> pairs;
    for (const auto& scene_candidates : candidates) {
      pairs.push_back(
          PairsAtThreshold(scene_candidates, static_cast<float>(threshold)));
    }
    points.push_back(MeanScores(scenes, pairs, "threshold", threshold));
  }
  return points;
}

void WriteGcnSensitivity(const std::vector<GcnSensitivityPoint>& points,
                         const std::string& title,
                         const std::string& dir) {
  CreateDirIfNotExists(dir);
  std::ostringstream csv;
  csv << "parameter,value,precision,recall,f,pairs_per_image\n";
  std::map<std::string, std::vector<const GcnSensitivityPoint*>> by_parameter;
  for (const auto& point : points) {
    csv << point.parameter << "," << point.value << "," << point.precision
        << "," << point.recall << "," << point.f << "," << point.pairs_per_image
        << "\n";
    by_parameter[point.parameter].push_back(&point);
  }
  WriteFileAtomically(JoinPaths(dir, "sensitivity.csv"), csv.str());
  for (const auto& [parameter, series] : by_parameter) {
    std::vector<double> x;
    LinePlotSeries precision{"precision", {}, false};
    LinePlotSeries recall{"recall", {}, true};
    LinePlotSeries f{"F-measure", {}, false};
    for (const GcnSensitivityPoint* point : series) {
      x.push_back(point->value);
      precision.y.push_back(point->precision);
      recall.y.push_back(point->recall);
      f.y.push_back(point->f);
    }
    WriteLinePlot(JoinPaths(dir, "sensitivity_" + parameter + ".png"),
                  title + ": " + parameter,
                  parameter,
                  x,
                  {precision, recall, f},
                  "precision / recall / F-measure");
  }
}

}  // namespace colmap_gcn
