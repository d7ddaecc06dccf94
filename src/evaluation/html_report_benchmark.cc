// The benchmark output folder's part of `gcn_report` (html_report.h): the
// paper's tables from results.json, with sortable columns, and the figures.
#include <map>

#include "evaluation/html_report.h"
#include "evaluation/sfm_metrics.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using html::Escape;
using html::Number;

std::string Int(const Json& json, const char* key) {
  return std::to_string(json.value(key, size_t{0}));
}

std::string Real(const Json& json, const char* key, int decimals) {
  const auto it = json.find(key);
  if (it == json.end() || !it->is_number()) return "-";
  return Number(it->get<double>(), decimals);
}

// Per method: the sums over its scenes, for the means table.
struct MethodMeans {
  int num_scenes = 0;
  double precision = 0, recall = 0, f = 0, useful = 0, registered = 0,
         seconds = 0;
};

std::string MeansTable(const std::vector<std::string>& order,
                       const std::map<std::string, MethodMeans>& means) {
  std::vector<std::vector<std::string>> rows;
  for (const std::string& method : order) {
    const auto it = means.find(method);
    if (it == means.end() || it->second.num_scenes == 0) continue;
    const MethodMeans& m = it->second;
    const double n = m.num_scenes;
    rows.push_back({Escape(method),
                    std::to_string(m.num_scenes),
                    Number(m.precision / n, 3),
                    Number(m.recall / n, 3),
                    Number(m.f / n, 3),
                    Number(m.useful / n, 3),
                    Number(m.registered / n, 3),
                    Number(m.seconds / n, 1)});
  }
  return html::SortableTable({"method",
                              "scenes",
                              "precision",
                              "recall",
                              "F-measure",
                              "UM/TAM",
                              "registered share",
                              "pairing + matching s"},
                             rows);
}

// The rows of the report's tables, one per scene and method.
struct Tables {
  std::vector<std::vector<std::string>> scenes, retrieval, matching, mapping,
      accuracy;
  std::map<std::string, MethodMeans> means;
  std::string figures;  // per scene, folded
};

void AddMethodRows(const std::string& scene_name,
                   const Json& m,
                   Tables* tables) {
  const std::string method = m.value("method", std::string());
  const std::string status = m.value("status", std::string());
  const Json r = m.value("retrieval", Json::object());
  const Json s = m.value("sfm", Json::object());
  const std::string key = Escape(scene_name), spec = Escape(method);
  if (status != "ok") {
    tables->matching.push_back(
        {key,
         spec,
         "-",
         "-",
         "-",
         "-",
         "-",
         "-",
         Escape(status + ": " + m.value("message", std::string()))});
    return;
  }
  tables->retrieval.push_back({key,
                               spec,
                               Int(m, "k"),
                               Real(r, "precision", 3),
                               Real(r, "recall", 3),
                               Real(r, "f_measure", 3),
                               Int(m, "tam"),
                               Int(r, "num_wrong_pairs")});
  tables->matching.push_back({key,
                              spec,
                              Int(m, "tam"),
                              Int(m, "um"),
                              Real(m, "um_over_tam", 3),
                              Int(m, "num_verified_wrong"),
                              Real(m, "pairing_seconds", 1),
                              Real(m, "matching_seconds", 1),
                              "ok"});
  tables->mapping.push_back({key,
                             spec,
                             Int(s, "num_images"),
                             Int(s, "num_registered"),
                             Int(s, "num_models"),
                             Int(s, "num_points3D"),
                             Int(s, "num_observations"),
                             Real(s, "mean_track_length", 2),
                             Real(s, "mean_reprojection_error", 3),
                             Real(m, "mapping_seconds", 1)});
  if (s.contains("pose_errors")) {
    const Json& p = s["pose_errors"];
    tables->accuracy.push_back({key,
                                spec,
                                Real(p, "median_rotation_error_deg", 2),
                                Real(p, "median_position_error", 4),
                                Real(p, "fraction_accurate", 3)});
  }
  MethodMeans& mean = tables->means[method];
  ++mean.num_scenes;
  mean.precision += r.value("precision", 0.0);
  mean.recall += r.value("recall", 0.0);
  mean.f += r.value("f_measure", 0.0);
  mean.useful += m.value("um_over_tam", 0.0);
  const double images = s.value("num_images", 0.0);
  mean.registered += images > 0 ? s.value("num_registered", 0.0) / images : 0.0;
  mean.seconds +=
      m.value("pairing_seconds", 0.0) + m.value("matching_seconds", 0.0);
}

void AddSceneRows(const std::string& output_path,
                  const Json& scene,
                  Tables* tables) {
  const std::string name = scene.value("name", std::string());
  tables->scenes.push_back({Escape(name),
                            Escape(scene.value("kind", std::string())),
                            Int(scene, "num_images"),
                            Int(scene, "num_matchable_pairs"),
                            Real(scene, "extraction_seconds", 1),
                            Escape(scene.value("status", std::string()) + " " +
                                   scene.value("message", std::string()))});
  for (const Json& method : scene.value("methods", Json::array())) {
    AddMethodRows(name, method, tables);
  }
  std::string scene_figures;
  for (const Json& figure : scene.value("figures", Json::array())) {
    const std::string path = JoinPaths(output_path, figure.get<std::string>());
    if (ExistsFile(path)) {
      scene_figures += html::InlinePng(path, figure.get<std::string>());
    }
  }
  if (!scene_figures.empty()) {
    tables->figures += "<details><summary>" + Escape(name) + "</summary>\n" +
                       scene_figures + "</details>\n";
  }
}

}  // namespace

std::string BenchmarkReportBody(const std::string& output_path,
                                const Json& results) {
  Tables tables;
  for (const Json& scene : results.value("scenes", Json::array())) {
    AddSceneRows(output_path, scene, &tables);
  }
  auto& [scenes, retrieval, matching, mapping, accuracy, means, figures] =
      tables;
  std::vector<std::string> order;
  for (const Json& method : results.value("methods", Json::array())) {
    order.push_back(method.is_string() ? method.get<std::string>()
                                       : method.value("spec", std::string()));
  }
  if (order.empty()) {
    for (const auto& [method, unused] : means) order.push_back(method);
  }

  std::string body = "<h1>Benchmark report</h1>\n<p class=\"sub\">" +
                     Escape(output_path) +
                     " &middot; click a column header to sort</p>\n";
  body +=
      "<pre>" + Escape(results.value("command", std::string())) + "</pre>\n";
  body += "<h2>Mean over scenes</h2>\n" + MeansTable(order, means);
  body += "<h2>Scenes</h2>\n" + html::SortableTable({"scene",
                                                     "kind",
                                                     "images",
                                                     "matchable pairs",
                                                     "extraction s",
                                                     "status"},
                                                    scenes);
  body += "<h2>Retrieval (the paper's Tables 1-2)</h2>\n" +
          html::SortableTable({"scene",
                               "method",
                               "k",
                               "precision",
                               "recall",
                               "F-measure",
                               "pairs (TAM)",
                               "wrong pairs"},
                              retrieval);
  body += "<h2>Matching (Tables 3, 5)</h2>\n" +
          html::SortableTable({"scene",
                               "method",
                               "TAM",
                               "UM",
                               "UM/TAM",
                               "verified wrong",
                               "pairing s",
                               "matching s",
                               "status"},
                              matching);
  body +=
      "<h2>Mapping (Tables 4, 6)</h2>\n" +
      html::SortableTable(SfmMetricColumns({"scene", "method"},
                                           {"reprojection px", "mapping s"}),
                          mapping);
  if (!accuracy.empty()) {
    body += "<h2>Camera accuracy against ground truth</h2>\n" +
            html::SortableTable({"scene",
                                 "method",
                                 "median rotation deg",
                                 "median position (scene extent)",
                                 "accurate share"},
                                accuracy);
  }
  if (!figures.empty()) body += "<h2>Figures</h2>\n" + figures;
  return body;
}

}  // namespace colmap_gcn
