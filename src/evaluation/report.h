#pragma once

#include <string>

#include "evaluation/results.h"

namespace colmap_gcn {

// The paper's tables as markdown, per scene and averaged over scenes:
// retrieval (Tables 1-2: precision, recall, F-measure, wrong pairs),
// matching (Tables 3, 5: UM/TAM, times), mapping (Tables 4, 6: registered
// images, models, points, observations, track length, reprojection error)
// and camera accuracy against ground truth.
std::string FormatBenchmarkReport(const BenchmarkResults& results);

// One row per scene and method, every number the report shows.
std::string FormatBenchmarkCsv(const BenchmarkResults& results);

// Writes <output_path>/report.md, results.csv and results.json.
void WriteBenchmarkReport(const BenchmarkResults& results,
                          const std::string& output_path);

}  // namespace colmap_gcn
