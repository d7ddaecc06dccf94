#include "evaluation/html_report.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>

#include "evaluation/view_graph_figure.h"
#include "pairing/pairs_io.h"
#include "scene/reconstruction.h"
#include "scene/reconstruction_stats.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"

namespace colmap_gcn {
namespace html {

std::string Escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string Base64(const std::string& bytes) {
  static const char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const unsigned v =
        (static_cast<unsigned char>(bytes[i]) << 16) |
        (two ? static_cast<unsigned char>(bytes[i + 1]) << 8 : 0u);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += two ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string InlinePng(const std::string& png_path, const std::string& alt) {
  return "<img alt=\"" + Escape(alt) + "\" src=\"data:image/png;base64," +
         Base64(ReadTextFile(png_path)) + "\">";
}

std::string SortableTable(const std::vector<std::string>& headers,
                          const std::vector<std::vector<std::string>>& rows) {
  std::string out = "<table class=\"sortable\"><thead><tr>";
  for (const std::string& header : headers) {
    out += "<th title=\"click to sort\">" + header + "</th>";
  }
  out += "</tr></thead><tbody>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (const std::string& cell : row) out += "<td>" + cell + "</td>";
    out += "</tr>\n";
  }
  return out + "</tbody></table>\n";
}

std::string Number(const double value, const int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, value);
  return buffer;
}

std::string Page(const std::string& title, const std::string& body) {
  return R"(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>)" +
         Escape(title) +
         R"(</title>
<style>
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,"DejaVu Sans",sans-serif;
margin:24px auto;max-width:1180px;padding:0 16px;color:#222;line-height:1.4}
h1{font-size:26px;margin:0 0 4px}h2{font-size:20px;margin:28px 0 8px;
border-bottom:1px solid #ddd;padding-bottom:4px}.sub{color:#666;margin:0 0 16px}
.cards{display:flex;flex-wrap:wrap;gap:12px}.card{border:1px solid #ddd;
border-radius:8px;padding:10px 14px;min-width:130px;background:#fafafa}
.card .v{font-size:24px;font-weight:600}.card .k{color:#555;font-size:13px}
table{border-collapse:collapse;margin:8px 0;font-size:14px}
th,td{border:1px solid #ddd;padding:4px 8px;text-align:left;vertical-align:top}
th{background:#f0f0f0;cursor:pointer;user-select:none;white-space:nowrap}
th.asc:after{content:" \25B2"}th.desc:after{content:" \25BC"}
tbody tr:nth-child(even){background:#fafafa}td.num{text-align:right}
img{max-width:100%;border:1px solid #eee}pre{background:#f6f6f6;padding:8px;
white-space:pre-wrap;word-break:break-all;font-size:13px}.bad{color:#b00}
.ok{color:#070}.note{color:#555;font-size:14px}
</style></head><body>
)" + body +
         R"(
<script>
document.querySelectorAll("table.sortable th").forEach(function (th) {
  th.addEventListener("click", function () {
    var row = th.parentNode, body = th.closest("table").tBodies[0];
    var col = Array.prototype.indexOf.call(row.children, th);
    var asc = !th.classList.contains("asc");
    row.querySelectorAll("th").forEach(function (h) {
      h.classList.remove("asc", "desc");
    });
    th.classList.add(asc ? "asc" : "desc");
    var rows = Array.prototype.slice.call(body.rows);
    rows.sort(function (a, b) {
      var x = a.cells[col].textContent, y = b.cells[col].textContent;
      var nx = parseFloat(x), ny = parseFloat(y);
      var c = (!isNaN(nx) && !isNaN(ny)) ? nx - ny : x.localeCompare(y);
      return asc ? c : -c;
    });
    rows.forEach(function (r) { body.appendChild(r); });
  });
});
</script>
</body></html>
)";
}

}  // namespace html

void HtmlReportOptions::Check() const {
  CHECK_OPTION(workspace_path, !workspace_path.empty(), "be given");
  CHECK_OPTION_GE(min_num_inliers, 0);
}

std::string WriteHtmlReport(const HtmlReportOptions& options) {
  options.Check();
  const std::string& workspace = options.workspace_path;
  if (!ExistsDir(workspace)) {
    ThrowError("--workspace_path ", workspace, " is not a folder");
  }
  const std::string output = options.output_path.empty()
                                 ? JoinPaths(workspace, "report.html")
                                 : options.output_path;
  std::string title;
  std::string body;
  const std::string results_path = JoinPaths(workspace, "results.json");
  if (ExistsFile(results_path)) {
    title = "colmap-gcn benchmark report";
    body = BenchmarkReportBody(workspace, ReadJsonFile(results_path));
  } else if (ExistsFile(JoinPaths(workspace, "database.db"))) {
    title = "colmap-gcn reconstruction report";
    body = ReconstructionReportBody(options);
  } else {
    ThrowError(workspace,
               " holds neither database.db (a gcn_reconstructor workspace) "
               "nor results.json (a gcn_benchmark output folder)");
  }
  WriteFileAtomically(output, html::Page(title, body));
  return output;
}

}  // namespace colmap_gcn
