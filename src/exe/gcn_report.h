#pragma once

namespace colmap_gcn {

// `colmap gcn_report --workspace_path WS`: one self-contained HTML page
// about a gcn_reconstructor workspace or a gcn_benchmark output folder
// (evaluation/html_report.h).
int RunGcnReport(int argc, char** argv);

}  // namespace colmap_gcn
