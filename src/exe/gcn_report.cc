#include "exe/gcn_report.h"

#include <cstdio>

#include "evaluation/html_report.h"
#include "util/option_manager.h"

namespace colmap_gcn {

int RunGcnReport(int argc, char** argv) {
  HtmlReportOptions options;
  OptionManager manager(
      "gcn_report",
      "Writes one self-contained HTML page (no network) about a "
      "gcn_reconstructor workspace or a gcn_benchmark output folder: "
      "settings, times, TAM/UM, models, the view graph and the images not "
      "registered, or the benchmark's tables.");
  manager.AddRequiredOption("workspace_path", &options.workspace_path);
  manager.AddDefaultOption("output_path",
                           &options.output_path,
                           "the page; empty: <workspace_path>/report.html");
  manager.AddDefaultOption("SiftMatching.min_num_inliers",
                           &options.min_num_inliers,
                           "inliers a verified pair (UM) needs");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] { options.Check(); });
  std::printf("%s\n", WriteHtmlReport(options).c_str());
  return 0;
}

}  // namespace colmap_gcn
