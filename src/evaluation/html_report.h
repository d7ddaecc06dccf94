#pragma once

#include <string>
#include <vector>

#include "evaluation/json_file.h"
#include "scene/database.h"

namespace colmap_gcn {

// `colmap gcn_report`: one self-contained HTML page about a workspace
// (images inline as base64, a few lines of inline JavaScript to sort the
// tables, nothing fetched from the network).
struct HtmlReportOptions {
  // A gcn_reconstructor workspace (database.db, sparse/, run.json) or a
  // gcn_benchmark output folder (results.json).
  std::string workspace_path = "";

  // Where the page goes; empty: <workspace_path>/report.html.
  std::string output_path = "";

  // COLMAP's --SiftMatching.min_num_inliers: a pair with fewer inliers does
  // not count as verified (UM).
  int min_num_inliers = kDefaultMinNumInliers;

  void Check() const;
};

// Writes the page and returns its path. Throws Error naming the problem
// when the workspace holds neither a database nor benchmark results.
std::string WriteHtmlReport(const HtmlReportOptions& options);

// The file gcn_reconstructor leaves in its workspace for the report: the
// command line, the settings, the stages' times and the matching counts.
constexpr char kRunSummaryFile[] = "run.json";

// Pieces of the page, for the report's parts and their tests.
namespace html {

// Text with &, <, >, " and ' escaped.
std::string Escape(const std::string& text);

// RFC 4648 base64 of the bytes.
std::string Base64(const std::string& bytes);

// <img> of a PNG file, inline as a data: URL.
std::string InlinePng(const std::string& png_path, const std::string& alt);

// A table whose columns sort on a click on their header (numerically when
// both cells are numbers). Cells are HTML (escape text first).
std::string SortableTable(const std::vector<std::string>& headers,
                          const std::vector<std::vector<std::string>>& rows);

// The whole page around `body`: styles and the sorting script inline.
std::string Page(const std::string& title, const std::string& body);

// A number with `decimals` digits after the point.
std::string Number(double value, int decimals);

}  // namespace html

// The reconstruction workspace's part of the page.
std::string ReconstructionReportBody(const HtmlReportOptions& options);

// The benchmark output folder's part of the page, from results.json.
std::string BenchmarkReportBody(const std::string& output_path,
                                const Json& results);

}  // namespace colmap_gcn
