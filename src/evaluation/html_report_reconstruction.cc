// The reconstruction workspace's part of `gcn_report` (html_report.h).
#include <algorithm>
#include <map>
#include <set>

#include "evaluation/html_report.h"
#include "evaluation/view_graph_figure.h"
#include "pairing/pairs_io.h"
#include "scene/reconstruction.h"
#include "scene/reconstruction_stats.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

using html::Escape;
using html::Number;

std::string Card(const std::string& value, const std::string& key) {
  return "<div class=\"card\"><div class=\"v\">" + value +
         "</div><div class=\"k\">" + key + "</div></div>";
}

std::string Num(const std::string& text) {
  return "<span class=\"num\">" + text + "</span>";
}

struct ModelRow {
  std::string path;
  ReconstructionStatistics stats;
};

// The pairs file of the run: run.json's, else gcn_matcher's default.
std::string PairsPath(const std::string& workspace, const Json& run) {
  const std::string from_run = run.value("pairs_path", std::string());
  if (!from_run.empty() && ExistsFile(from_run)) return from_run;
  const std::string fallback =
      JoinPaths(workspace, "database.db") + ".pairs.txt";
  return ExistsFile(fallback) ? fallback : "";
}

std::string SummaryCards(size_t num_images,
                         size_t num_registered,
                         const std::vector<ModelRow>& models,
                         size_t tam,
                         size_t um) {
  size_t points = 0;
  for (const ModelRow& model : models) points += model.stats.num_points3D;
  const size_t exhaustive = num_images * (num_images - 1) / 2;
  std::string cards = "<div class=\"cards\">";
  cards += Card(std::to_string(num_images), "images");
  cards +=
      Card(std::to_string(num_registered) + " / " + std::to_string(num_images),
           "registered images (any model)");
  cards += Card(std::to_string(models.size()), "models");
  cards += Card(std::to_string(points), "3-D points");
  cards += Card(std::to_string(tam),
                "pairs matched (TAM), of " + std::to_string(exhaustive) +
                    " for exhaustive matching");
  cards += Card(std::to_string(um), "verified pairs (UM)");
  cards += Card(tam == 0 ? "-" : Number(static_cast<double>(um) / tam, 3),
                "UM per TAM: share of matched pairs that verified");
  return cards + "</div>\n";
}

std::string UnregisteredSection(const std::vector<std::string>& names,
                                const std::set<std::string>& registered,
                                const std::vector<ImageNamePair>& attempted,
                                const std::vector<ImageNamePair>& verified) {
  std::map<std::string, std::set<std::string>> tried, good;
  for (const auto& [a, b] : attempted) tried[a].insert(b), tried[b].insert(a);
  for (const auto& [a, b] : verified) good[a].insert(b), good[b].insert(a);
  std::vector<std::vector<std::string>> rows;
  for (const std::string& name : names) {
    if (registered.count(name) > 0) continue;
    std::vector<std::string> partners;
    for (const std::string& other : tried[name]) {
      const bool ok = good[name].count(other) > 0;
      partners.push_back("<span class=\"" + std::string(ok ? "ok" : "bad") +
                         "\">" + Escape(other) + (ok ? " &#10003;" : "") +
                         "</span>");
    }
    const size_t num_good = good[name].size();
    const std::string why =
        tried[name].empty()
            ? "never paired: the pair selection chose no partner"
        : num_good == 0 ? "no pair verified: no partner shares enough "
                          "matches with it"
                        : "verified pairs exist but the mapper could not "
                          "register it (too few 2D-3D matches)";
    rows.push_back({Escape(name),
                    std::to_string(tried[name].size()),
                    std::to_string(num_good),
                    why,
                    partners.empty() ? "-" : StringJoin(partners, ", ")});
  }
  std::string out =
      "<h2>Images not registered (" + std::to_string(rows.size()) + ")</h2>\n";
  if (rows.empty()) {
    return out + "<p class=\"ok\">All " + std::to_string(names.size()) +
           " images are registered.</p>\n";
  }
  out +=
      "<p class=\"note\">Each image with the images it was matched with; "
      "<span class=\"ok\">green &#10003;</span>: the pair verified, "
      "<span class=\"bad\">red</span>: it did not.</p>\n";
  return out +
         html::SortableTable(
             {"image", "matched with", "verified", "likely reason", "partners"},
             rows);
}

std::string SettingsSection(const Json& run) {
  std::string out = "<h2>Settings</h2>\n";
  if (run.empty()) {
    return out +
           "<p class=\"note\">No run.json in the workspace (it was not made "
           "by gcn_reconstructor): settings and times unknown.</p>\n";
  }
  out += "<pre>" + Escape(run.value("command", std::string())) + "</pre>\n";
  std::vector<std::vector<std::string>> rows;
  if (run.contains("settings")) {
    for (const auto& [key, value] : run["settings"].items()) {
      rows.push_back({Escape(key),
                      Escape(value.is_string() ? value.get<std::string>()
                                               : value.dump())});
    }
  }
  return out + html::SortableTable({"setting", "value"}, rows);
}

std::string TimesSection(const Json& run) {
  if (!run.contains("stages")) return "";
  std::vector<std::vector<std::string>> rows;
  double total = 0.0;
  for (const Json& stage : run["stages"]) {
    const double seconds = stage.value("seconds", 0.0);
    total += seconds;
    rows.push_back(
        {Escape(stage.value("name", std::string())), Num(Number(seconds, 1))});
  }
  rows.push_back({"<b>total</b>", Num("<b>" + Number(total, 1) + "</b>")});
  return "<h2>Time per stage (seconds)</h2>\n" +
         html::SortableTable({"stage", "seconds"}, rows);
}

std::string ModelsSection(const std::vector<ModelRow>& models,
                          size_t num_images) {
  std::vector<std::vector<std::string>> rows;
  for (const ModelRow& model : models) {
    const ReconstructionStatistics& s = model.stats;
    rows.push_back({Escape(model.path),
                    Num(std::to_string(s.num_registered_images) + " / " +
                        std::to_string(num_images)),
                    Num(std::to_string(s.num_points3D)),
                    Num(std::to_string(s.num_observations)),
                    Num(Number(s.mean_track_length, 2)),
                    Num(Number(s.mean_reprojection_error, 3))});
  }
  std::string out = "<h2>Models (" + std::to_string(models.size()) + ")</h2>\n";
  if (rows.empty()) {
    return out + "<p class=\"bad\">The mapper produced no model.</p>\n";
  }
  return out + html::SortableTable({"model",
                                    "registered images",
                                    "points",
                                    "observations",
                                    "mean track length",
                                    "mean reprojection error (px)"},
                                   rows);
}

}  // namespace

std::string ReconstructionReportBody(const HtmlReportOptions& options) {
  const std::string& workspace = options.workspace_path;
  const std::string run_path = JoinPaths(workspace, kRunSummaryFile);
  const Json run =
      ExistsFile(run_path) ? ReadJsonFile(run_path) : Json::object();

  const std::string pairs_path = PairsPath(workspace, run);
  MatchedViewGraph graph = ReadMatchedViewGraph(
      JoinPaths(workspace, "database.db"), pairs_path, options.min_num_inliers);
  std::vector<ModelRow> models;
  for (const std::string& path :
       ListSparseModels(JoinPaths(workspace, "sparse"))) {
    Reconstruction reconstruction;
    reconstruction.Read(path);
    models.push_back({path, ComputeReconstructionStatistics(reconstruction)});
    for (const auto& [id, image] : reconstruction.images) {
      graph.registered.insert(image.name);
    }
  }
  graph.registration_known = true;
  const size_t n = graph.image_names.size();
  const size_t tam = run.value("tam", graph.attempted.size());
  const size_t um = run.value("um", graph.verified.size());
  const std::string pairing = run.value("pairing", std::string());
  graph.title = "View graph" + (pairing.empty() ? "" : " (" + pairing + ")") +
                ": " + std::to_string(graph.registered.size()) + " of " +
                std::to_string(n) + " images registered";
  const std::string figure = JoinPaths(workspace, "view_graph.png");
  WriteMatchedViewGraphImage(figure, graph);

  std::string body =
      "<h1>Reconstruction report</h1>\n<p class=\"sub\">" + Escape(workspace) +
      (pairing.empty() ? "" : " &middot; pairing " + Escape(pairing)) +
      "</p>\n";
  body += SummaryCards(n, graph.registered.size(), models, tam, um);
  body += "<h2>View graph</h2>\n" + html::InlinePng(figure, "view graph");
  body += UnregisteredSection(
      graph.image_names, graph.registered, graph.attempted, graph.verified);
  body += ModelsSection(models, n);
  body += TimesSection(run);
  body += SettingsSection(run);
  body += "<p class=\"note\">Files: database.db, " +
          Escape(pairs_path.empty() ? "(no pairs file)" : pairs_path) +
          ", colmap.log (every COLMAP call with its full output).</p>\n";
  return body;
}

}  // namespace colmap_gcn
