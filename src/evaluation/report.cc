#include "evaluation/report.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "evaluation/sfm_metrics.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

std::string Format(const char* format, double value) {
  if (!std::isfinite(value)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

std::string Count(size_t value) { return std::to_string(value); }

// A markdown table builder.
class Table {
 public:
  explicit Table(const std::vector<std::string>& header) : header_(header) {}
  void Row(const std::vector<std::string>& cells) { rows_.push_back(cells); }
  bool Empty() const { return rows_.empty(); }
  std::string Str() const {
    std::ostringstream out;
    const auto line = [&](const std::vector<std::string>& cells) {
      out << "|";
      for (size_t i = 0; i < header_.size(); ++i) {
        out << " " << (i < cells.size() ? cells[i] : "") << " |";
      }
      out << "\n";
    };
    line(header_);
    out << "|";
    for (size_t i = 0; i < header_.size(); ++i)
      out << (i == 0 ? "---|" : "---:|");
    out << "\n";
    for (const auto& row : rows_) line(row);
    return out.str();
  }

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

std::string MethodLabel(const MethodResult& result) {
  std::string label = result.method;
  // Show the cap when k was limited by the scene size.
  const size_t colon = result.method.find(':');
  if (result.k > 0 && colon != std::string::npos &&
      std::to_string(result.k) != result.method.substr(colon + 1)) {
    label += " (k=" + std::to_string(result.k) + ")";
  }
  if (result.Ok() && !result.message.empty()) {
    // e.g. "same pairs as exhaustive": the row repeats that method's run.
    label += " (" + result.message + ")";
  }
  return label;
}

std::string StatusRow(const MethodResult& result) {
  std::string message = result.message;
  if (message.size() > 120) message = message.substr(0, 117) + "...";
  for (char& c : message) {
    if (c == '|') c = '/';
  }
  return result.status + (message.empty() ? "" : ": " + message);
}

const MethodResult* FindExhaustive(const SceneResult& scene) {
  for (const MethodResult& method : scene.methods) {
    if (method.method == "exhaustive" && method.Ok()) return &method;
  }
  return nullptr;
}

// Merged collections: what crosses between the collection's places, and
// whether each place still reconstructs as it does alone.
void CollectionSection(const SceneResult& scene, std::ostringstream* out) {
  const size_t num_pairs = scene.num_images * (scene.num_images - 1) / 2;
  const MethodResult* exhaustive = FindExhaustive(scene);
  // Without an exhaustive run, its time is estimated from this run's
  // pooled per-pair matching time (every method's seconds over its pairs).
  double seconds = 0;
  size_t pairs = 0;
  for (const MethodResult& method : scene.methods) {
    if (!method.Ok() || !method.same_as.empty()) continue;
    seconds += method.matching_seconds;
    pairs += method.num_attempted;
  }
  const double per_pair = pairs > 0 ? seconds / pairs : NAN;
  const double exhaustive_seconds = exhaustive != nullptr
                                        ? exhaustive->matching_seconds
                                        : per_pair * num_pairs;
  *out << "### Collection: pairs across its scenes, each scene's "
          "registration\n\n";
  if (exhaustive != nullptr) {
    *out << "Exhaustive matching time: measured, "
         << Format("%.1f", exhaustive_seconds) << " s.\n\n";
  } else {
    *out << "Exhaustive matching time: **estimated**, " << num_pairs
         << " pairs x " << Format("%.3f", per_pair)
         << " s (this run's matching seconds over its attempted pairs, all "
            "methods) = "
         << Format("%.0f", exhaustive_seconds) << " s.\n\n";
  }
  Table crossing({"method",
                  "TAM",
                  "cross-scene attempted",
                  "% of TAM",
                  "cross-scene verified",
                  "pairing + matching (s)",
                  "/ exhaustive",
                  "models",
                  "mixed models",
                  "scenes >= 95% of alone"});
  std::vector<std::string> header = {"scene", "images", "alone (exhaustive)"};
  std::vector<const MethodResult*> shown;
  for (const MethodResult& method : scene.methods) {
    if (!method.Ok() || method.collection.scenes.empty()) continue;
    shown.push_back(&method);
    header.push_back(MethodLabel(method));
    size_t kept = 0;
    for (const auto& [name, entry] : method.collection.scenes) {
      const auto alone = scene.registered_alone.find(name);
      if (alone != scene.registered_alone.end() &&
          entry.num_registered >= 0.95 * alone->second) {
        ++kept;
      }
    }
    const double total = method.pairing_seconds + method.matching_seconds;
    crossing.Row(
        {MethodLabel(method),
         Count(method.num_attempted),
         Count(method.num_cross_scene_attempted),
         Format("%.2f",
                method.num_attempted == 0
                    ? NAN
                    : 100.0 * method.num_cross_scene_attempted /
                          method.num_attempted),
         Count(method.num_cross_scene_verified),
         Format("%.1f", total),
         Format("%.3f", total / exhaustive_seconds),
         Count(method.collection.num_models),
         Count(method.collection.num_mixed_models),
         scene.registered_alone.empty()
             ? "-"
             : Count(kept) + "/" + Count(method.collection.scenes.size())});
  }
  *out << crossing.Str() << "\n";
  if (shown.empty()) return;
  Table per_scene(header);
  for (const auto& [name, entry] : shown.front()->collection.scenes) {
    const auto alone = scene.registered_alone.find(name);
    std::vector<std::string> row = {
        name,
        Count(entry.num_images),
        alone == scene.registered_alone.end() ? "-" : Count(alone->second)};
    for (const MethodResult* method : shown) {
      const auto found = method->collection.scenes.find(name);
      const size_t registered = found == method->collection.scenes.end()
                                    ? 0
                                    : found->second.num_registered;
      const bool below = alone != scene.registered_alone.end() &&
                         registered < 0.95 * alone->second;
      row.push_back(below ? "**" + Count(registered) + "**"
                          : Count(registered));
    }
    per_scene.Row(row);
  }
  *out << "Registered images per scene (its best model; **bold**: below 95 % "
          "of the scene alone):\n\n"
       << per_scene.Str() << "\n";
}

// One scene's per-method tables: retrieval, matching, mapping and, with
// ground-truth cameras, poses.
struct SceneTables {
  Table retrieval{{"method",
                   "k",
                   "pairs",
                   "true pos.",
                   "precision",
                   "recall",
                   "F-measure",
                   "wrong pairs"}};
  Table matching{{"method",
                  "UM/TAM",
                  "ratio",
                  "verified wrong",
                  "pairing (s)",
                  "matching (s)",
                  "speedup vs exhaustive"}};
  Table mapping{
      SfmMetricColumns({"method"}, {"reproj. error (px)", "mapping (s)"})};
  Table pose{{"method",
              "aligned",
              "median rot. (deg)",
              "median pos. (% extent)",
              "rot. ok",
              "pos. ok",
              "accurate"}};
};

// One method's rows (a failed or unavailable one: its status in each).
void AddMethodRows(const SceneResult& scene,
                   const MethodResult& method,
                   const MethodResult* exhaustive,
                   SceneTables* tables) {
  Table* retrieval = &tables->retrieval;
  Table* matching = &tables->matching;
  Table* mapping = &tables->mapping;
  Table* pose = &tables->pose;
  const std::string label = MethodLabel(method);
  if (!method.Ok()) {
    const std::string status = StatusRow(method);
    retrieval->Row({label, status});
    matching->Row({label, status});
    mapping->Row({label, status});
    if (scene.has_gt_cameras) pose->Row({label, status});
    return;
  }
  const PairSetScore& r = method.retrieval;
  retrieval->Row({label,
                  method.k > 0 ? std::to_string(method.k) : "-",
                  Count(r.num_pairs),
                  Count(r.num_true_positives),
                  Format("%.3f", r.precision),
                  Format("%.3f", r.recall),
                  Format("%.3f", r.f_measure),
                  Count(r.num_wrong_pairs)});
  std::string speedup = "-";
  if (exhaustive != nullptr && method.matching_seconds > 0) {
    speedup =
        "x" +
        Format("%.2f", exhaustive->matching_seconds / method.matching_seconds);
  }
  matching->Row({label,
                 Count(method.num_verified) + "/" + Count(method.num_attempted),
                 Format("%.3f", method.UsefulRatio()),
                 Count(method.num_verified_wrong),
                 Format("%.2f", method.pairing_seconds),
                 Format("%.1f", method.matching_seconds),
                 speedup});
  const SfmMetrics& s = method.sfm;
  mapping->Row({label,
                Count(s.num_images),
                Count(s.num_registered),
                Count(s.num_models),
                Count(s.num_points3D),
                Count(s.num_observations),
                Format("%.3f", s.mean_track_length),
                Format("%.3f", s.mean_reprojection_error),
                Format("%.1f", method.mapping_seconds)});
  if (scene.has_gt_cameras && s.has_pose_errors) {
    const PoseErrors& p = s.pose_errors;
    if (!p.aligned) {
      pose->Row({label,
                 Count(p.num_evaluated) + "/" + Count(p.num_gt_images),
                 "-",
                 "-",
                 "0%",
                 "0%",
                 "0%"});
    } else {
      pose->Row({label,
                 Count(p.num_evaluated) + "/" + Count(p.num_gt_images),
                 Format("%.2f", p.median_rotation_error_deg),
                 Format("%.2f", 100 * p.median_position_error),
                 Format("%.0f%%", 100 * p.fraction_rotation_ok),
                 Format("%.0f%%", 100 * p.fraction_position_ok),
                 Format("%.0f%%", 100 * p.fraction_accurate)});
    }
  }
}

// What was made before pairing and is not in pairing_s (a vocabulary tree,
// as a user downloads one).
std::string PreparedNote(const SceneResult& scene) {
  std::string note;
  for (const MethodResult& method : scene.methods) {
    if (method.prepare_seconds <= 0) continue;
    // A later method of the same family finds the tree already made.
    const bool reused = method.prepare_seconds < 0.05;
    note += (note.empty() ? "" : ", ") + method.method + ": " +
            (reused ? std::string("reused")
                    : Format("%.1f", method.prepare_seconds) + " s");
  }
  if (note.empty()) return "";
  return "\n_Made before pairing, as a user downloads it, and not in "
         "\"pairing (s)\": the vocabulary tree (" +
         note + ")._\n";
}

void SceneSection(const SceneResult& scene, std::ostringstream* out) {
  *out << "## " << scene.name << "\n\n";
  if (scene.status != "ok") {
    *out << "**" << scene.status << "**: " << scene.message << "\n\n";
    return;
  }
  *out << scene.num_images << " images (" << scene.kind
       << "); labels: " << scene.label_source << ", "
       << scene.num_matchable_pairs << " matchable pairs among "
       << scene.num_labelled_images << " labelled images; feature extraction "
       << Format("%.1f", scene.extraction_seconds) << " s.\n\n";
  if (scene.methods.empty()) return;  // --methods none: prepared only
  std::set<std::string> sessions;
  for (const MethodResult& method : scene.methods) {
    if (method.Ok() && !method.session.empty()) sessions.insert(method.session);
  }
  if (sessions.size() > 1) {
    *out << "_Note: matching times on this scene come from " << sessions.size()
         << " different runs (cached results); rerun into a fresh output "
            "folder for comparable times._\n\n";
  }

  SceneTables tables;
  const MethodResult* exhaustive = FindExhaustive(scene);
  for (const MethodResult& method : scene.methods) {
    AddMethodRows(scene, method, exhaustive, &tables);
  }
  *out << "### Matchable image retrieval (Tables 1-2)\n\n"
       << tables.retrieval.Str() << "\n### Matching (Tables 3, 5)\n\n"
       << tables.matching.Str() << PreparedNote(scene)
       << "\n### Mapping, largest model (Tables 4, 6)\n\n"
       << tables.mapping.Str();
  if (!tables.pose.Empty()) {
    *out << "\n### Cameras against ground truth (similarity-aligned)\n\n"
         << tables.pose.Str();
  }
  if (scene.is_collection) {
    *out << "\n";
    CollectionSection(scene, out);
  }
  if (!scene.figures.empty()) {
    *out << "\n";
    for (const std::string& figure : scene.figures) {
      *out << "![" << figure << "](" << figure << ")\n";
    }
  }
  *out << "\n";
}

}  // namespace

std::string FormatBenchmarkReport(const BenchmarkResults& results) {
  std::ostringstream out;
  out << "# colmap-gcn benchmark\n\n";
  if (!results.command.empty()) {
    out << "```sh\n" << results.command << "\n```\n\n";
  }
  out << "Labels: a pair is matchable when MO >= "
      << Format("%.2f", results.label_options.min_overlap) << " or CT >= "
      << Format("%.2f", results.label_options.min_common_track_ratio)
      << "; wrong pairs share no surface / 3D point under the ground truth. "
         "Accurate cameras: rotation error <= "
      << Format("%.1f", results.pose_options.max_rotation_error_deg)
      << " deg and position error <= "
      << Format("%.1f", 100 * results.pose_options.max_position_error)
      << "% of the scene extent, after a similarity alignment of the "
         "largest model's camera centres; fractions are over all images "
         "with ground truth.\n\n";

  if (results.methods.empty()) {
    out << "No methods run (`--methods none`): the scenes below are "
           "prepared (features and labels) for `colmap gcn_train`.\n\n";
    for (const SceneResult& scene : results.scenes) SceneSection(scene, &out);
    return out.str();
  }
  // Averages over scenes (paper Tables 1-2 average over GL3D scenes).
  out << "## Average over scenes\n\n";
  Table average({"method",
                 "scenes",
                 "precision",
                 "recall",
                 "F-measure",
                 "wrong pairs",
                 "UM/TAM",
                 "verified wrong",
                 "registered",
                 "accurate cameras"});
  for (const std::string& spec : results.methods) {
    std::vector<PairSetScore> retrieval;
    double ratio = 0, accurate = 0;
    size_t verified_wrong = 0, registered = 0, images = 0, with_pose = 0;
    size_t unavailable = 0;
    for (const SceneResult& scene : results.scenes) {
      for (const MethodResult& method : scene.methods) {
        if (method.method != spec) continue;
        if (!method.Ok()) {
          ++unavailable;
          continue;
        }
        retrieval.push_back(method.retrieval);
        ratio += method.UsefulRatio();
        verified_wrong += method.num_verified_wrong;
        registered += method.sfm.num_registered;
        images += method.sfm.num_images;
        if (method.sfm.has_pose_errors) {
          accurate += method.sfm.pose_errors.fraction_accurate;
          ++with_pose;
        }
      }
    }
    if (retrieval.empty()) {
      average.Row({spec, "0", unavailable > 0 ? "unavailable" : "-"});
      continue;
    }
    const PairSetScore mean = AverageRetrievalMetrics(retrieval);
    average.Row(
        {spec,
         Count(retrieval.size()),
         Format("%.3f", mean.precision),
         Format("%.3f", mean.recall),
         Format("%.3f", mean.f_measure),
         Count(mean.num_wrong_pairs),
         Format("%.3f", ratio / retrieval.size()),
         Count(verified_wrong),
         Count(registered) + "/" + Count(images),
         with_pose > 0 ? Format("%.0f%%", 100 * accurate / with_pose) : "-"});
  }
  out << average.Str() << "\n";
  for (const SceneResult& scene : results.scenes) SceneSection(scene, &out);
  return out.str();
}

std::string FormatBenchmarkCsv(const BenchmarkResults& results) {
  std::ostringstream out;
  out << "scene,method,status,k,tam,um,um_over_tam,verified_wrong,"
         "pairing_s,matching_s,mapping_s,precision,recall,f_measure,"
         "true_positives,matchable,wrong_pairs,images,registered,models,"
         "points,observations,track_length,reprojection_error,"
         "median_rotation_deg,median_position_rel,fraction_accurate\n";
  for (const SceneResult& scene : results.scenes) {
    for (const MethodResult& m : scene.methods) {
      const SfmMetrics& s = m.sfm;
      const bool pose = s.has_pose_errors && s.pose_errors.aligned;
      out << scene.name << "," << m.method << "," << m.status << "," << m.k
          << "," << m.num_attempted << "," << m.num_verified << ","
          << Format("%.4f", m.UsefulRatio()) << "," << m.num_verified_wrong
          << "," << Format("%.3f", m.pairing_seconds) << ","
          << Format("%.3f", m.matching_seconds) << ","
          << Format("%.3f", m.mapping_seconds) << ","
          << Format("%.4f", m.retrieval.precision) << ","
          << Format("%.4f", m.retrieval.recall) << ","
          << Format("%.4f", m.retrieval.f_measure) << ","
          << m.retrieval.num_true_positives << "," << m.retrieval.num_matchable
          << "," << m.retrieval.num_wrong_pairs << "," << s.num_images << ","
          << s.num_registered << "," << s.num_models << "," << s.num_points3D
          << "," << s.num_observations << ","
          << Format("%.4f", s.mean_track_length) << ","
          << Format("%.4f", s.mean_reprojection_error) << ","
          << (pose ? Format("%.4f", s.pose_errors.median_rotation_error_deg)
                   : "")
          << ","
          << (pose ? Format("%.5f", s.pose_errors.median_position_error) : "")
          << ","
          << (s.has_pose_errors
                  ? Format("%.4f", s.pose_errors.fraction_accurate)
                  : "")
          << "\n";
    }
  }
  return out.str();
}

void WriteBenchmarkReport(const BenchmarkResults& results,
                          const std::string& output_path) {
  CreateDirIfNotExists(output_path);
  WriteFileAtomically(JoinPaths(output_path, "report.md"),
                      FormatBenchmarkReport(results));
  WriteFileAtomically(JoinPaths(output_path, "results.csv"),
                      FormatBenchmarkCsv(results));
  WriteJsonFile(JoinPaths(output_path, "results.json"),
                BenchmarkResultsToJson(results));
}

}  // namespace colmap_gcn
