#include "exe/gcn_benchmark.h"

#include <algorithm>
#include <iostream>

#include "controllers/colmap_runner.h"
#include "controllers/gcn_matching.h"
#include "controllers/pair_generators.h"
#include "evaluation/benchmark.h"
#include "evaluation/html_report.h"
#include "evaluation/method.h"
#include "evaluation/report.h"
#include "exe/gcn_matcher.h"
#include "util/error.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

// Each --methods entry chooses the generator and its depth (knn:25): the
// flags for them are refused rather than silently overridden.
void CheckNoMethodFlags(const OptionManager& manager,
                        GcnMatchingOptions* options) {
  std::vector<std::string> flags = {"--GcnMatching.pairing"};
  for (const std::string& name : PairGenerators().Names()) {
    const int* depth = PairGenerators().Depth(name, &options->generators);
    const std::string flag = depth ? manager.FlagName(depth) : "";
    if (!flag.empty() &&
        std::find(flags.begin(), flags.end(), flag) == flags.end()) {
      flags.push_back(flag);
    }
  }
  for (const std::string& flag : flags) {
    if (!manager.IsGiven(flag.substr(2))) continue;
    ThrowError(flag,
               " must not be given to gcn_benchmark (each --methods entry "
               "sets it) (got \"",
               manager.GivenValue(flag.substr(2)),
               "\")");
  }
}

}  // namespace

int RunGcnBenchmark(int argc, char** argv) {
  BenchmarkOptions options;
  OptionManager manager(
      "gcn_benchmark",
      "Runs pair-selection methods on scenes (extraction once per scene, "
      "each method's matching and mapping on a copy) and writes the paper's "
      "tables to <output_path>/report.md, results.csv, results.json and "
      "figures/. Cached per scene and method: rerunning resumes.");
  manager.AddRequiredOption(
      "datasets",
      &options.datasets,
      "comma list of scene folders (images/ + gt/, or 1DSfM list.txt + "
      "bundle.out) or synth:<family>:<n>[:seed]");
  manager.AddDefaultOption("methods", &options.methods, BenchmarkMethodsHelp());
  manager.AddRequiredOption("output_path", &options.output_path);
  manager.AddDefaultOption("Benchmark.tau_mo",
                           &options.labels.min_overlap,
                           "matchable when overlap >= tau_mo");
  manager.AddDefaultOption("Benchmark.tau_ct",
                           &options.labels.min_common_track_ratio,
                           "... or common-track ratio >= tau_ct");
  manager.AddDefaultOption(
      "Benchmark.label_max_viewpoint_change_deg",
      &options.label_pair_filter.max_viewpoint_change_deg,
      "labels of GT-camera scenes: match only pairs whose poses allow a "
      "viewpoint change below this (degrees) at a common point; 0: all "
      "pairs");
  manager.AddDefaultOption("Benchmark.max_rotation_error_deg",
                           &options.pose.max_rotation_error_deg,
                           "accurate camera: rotation error below this");
  manager.AddDefaultOption("Benchmark.max_position_error",
                           &options.pose.max_position_error,
                           "... and position error below this fraction of "
                           "the scene extent");
  manager.AddDefaultOption("Benchmark.mapper_num_threads",
                           &options.mapper_num_threads,
                           "1: repeatable mapper runs; -1: all cores");
  manager.AddDefaultOption("Benchmark.mapper_min_model_size",
                           &options.mapper_min_model_size,
                           "smaller models are discarded by the mapper");
  manager.AddDefaultOption("Benchmark.alone_results_path",
                           &options.alone_results_path,
                           "merged collections: results.json of their scenes "
                           "benchmarked alone with exhaustive matching");
  manager.AddDefaultOption(
      "Benchmark.verbose", &options.verbose, "show all of COLMAP's output");
  manager.AddDefaultOption("Benchmark.keep_going",
                           &options.keep_going,
                           "exit 0 even when scenes or methods failed");
  // COLMAP's names for options the benchmark sets itself: read here, passed
  // once.
  manager.AddAliasOption("Mapper.num_threads",
                         &options.mapper_num_threads,
                         "= --Benchmark.mapper_num_threads");
  manager.AddAliasOption("Mapper.min_model_size",
                         &options.mapper_min_model_size,
                         "= --Benchmark.mapper_min_model_size");
  manager.AddDefaultOption("ImageReader.single_camera",
                           &options.single_camera,
                           "1: one camera per scene, 0: one per image; -1: "
                           "as the dataset says");
  manager.AddPassThroughPrefix("ImageReader.");
  manager.AddPassThroughPrefix("SiftExtraction.");
  manager.AddPassThroughPrefix("SiftMatching.");
  manager.AddPassThroughPrefix("Mapper.");
  AddGcnMatchingOptions(&manager, &options.gcn_matching);
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  const auto& args = manager.PassThroughArguments();
  options.extraction_args =
      ArgumentsWithPrefix(args, {"ImageReader.", "SiftExtraction."});
  options.matching_args = ArgumentsWithPrefix(args, {"SiftMatching."});
  options.mapper_args = ArgumentsWithPrefix(args, {"Mapper."});
  CheckNoMethodFlags(manager, &options.gcn_matching);
  manager.Check([&] { options.Check(); });
  CheckColmapArguments(args, options.colmap_exe);
  std::vector<std::string> command = {"colmap"};
  for (int i = 0; i < argc; ++i) command.push_back(ShellQuote(argv[i]));
  options.command = StringJoin(command, " ");

  const BenchmarkResults results = RunBenchmark(options);
  std::cout << FormatBenchmarkReport(results) << std::flush;
  HtmlReportOptions report_options;
  report_options.workspace_path = options.output_path;
  report_options.min_num_inliers =
      options.gcn_matching.matching.min_num_inliers;
  std::cerr << "[gcn_benchmark] report: " << options.output_path
            << "/report.md and " << WriteHtmlReport(report_options) << "\n";
  // A failed scene or method does not cost the others' results, but the
  // run failed: exit 1 unless --Benchmark.keep_going.
  const std::vector<std::string> failures = BenchmarkFailures(results);
  if (failures.empty()) return 0;
  std::cerr << "[gcn_benchmark] " << failures.size()
            << " failure(s) (see the report):\n";
  for (const std::string& failure : failures) {
    std::cerr << "[gcn_benchmark]   " << failure << "\n";
  }
  if (options.keep_going) return 0;
  std::cerr << "ERROR: gcn_benchmark: " << failures.size() << " failure(s) in "
            << results.scenes.size()
            << " scene(s); --Benchmark.keep_going 1 exits 0 anyway\n";
  return 1;
}

}  // namespace colmap_gcn
