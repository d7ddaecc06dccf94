#include "evaluation/benchmark.h"

#include <string>
#include <vector>

#include "controllers/pair_generators.h"
#include "evaluation/benchmark_runner.h"
#include "evaluation/dataset.h"
#include "evaluation/method.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"
#include "util/string.h"

namespace colmap_gcn {

PairMatchingOptions BenchmarkOptions::MatchingOptions() const {
  PairMatchingOptions matching;
  matching.colmap_args = matching_args;
  matching.min_num_inliers = gcn_matching.matching.min_num_inliers;
  matching.lookalikes_unverified = gcn_matching.filter_lookalikes;
  matching.lookalike_filter = gcn_matching.lookalike_filter;
  return matching;
}

void BenchmarkOptions::Check() const {
  CHECK_OPTION(datasets, !datasets.empty(), "name at least one dataset");
  CHECK_OPTION(methods, !methods.empty(), "name methods (or none)");
  CHECK_OPTION(output_path, !output_path.empty(), "name a folder");
  labels.Check();
  pose.Check();
  label_pair_filter.Check();
  CHECK_OPTION_GE(single_camera, -1);
  CHECK_OPTION_NUM_THREADS(mapper_num_threads);
  CHECK_OPTION_GE(mapper_min_model_size, 0);
  CHECK_OPTION(alone_results_path,
               alone_results_path.empty() || ExistsFile(alone_results_path),
               "no such file");
  // The options of every generator a method uses, before any work.
  for (const BenchmarkMethod& method : ParseBenchmarkMethods(methods)) {
    if (!method.IsOracle()) {
      PairGenerators().Check(method.pairing, gcn_matching.generators);
    }
  }
  gcn_matching.matching.Check();
}

namespace {

std::vector<std::string> BenchmarkDatasetProblems(
    const BenchmarkOptions& options) {
  std::vector<std::string> problems;
  for (const DatasetSpec& spec : ParseDatasetSpecs(options.datasets)) {
    try {
      CheckDataset(spec);
    } catch (const Error& error) {
      problems.push_back(error.what());
    }
  }
  return problems;
}

}  // namespace

BenchmarkResults RunBenchmark(const BenchmarkOptions& options) {
  options.Check();
  ParseBenchmarkMethods(options.methods);
  const std::vector<std::string> problems = BenchmarkDatasetProblems(options);
  if (!problems.empty()) {
    ThrowError(StringJoin(problems, "; "));
  }
  return internal::BenchmarkRunner(options).Run();
}

std::vector<std::string> BenchmarkFailures(const BenchmarkResults& results) {
  std::vector<std::string> failures;
  for (const SceneResult& scene : results.scenes) {
    if (scene.status != "ok") {
      failures.push_back(scene.name + ": " + scene.message);
      continue;
    }
    for (const MethodResult& method : scene.methods) {
      if (!method.Ok()) {
        failures.push_back(scene.name + "/" + method.method + " " +
                           method.status + ": " + method.message);
      }
    }
  }
  return failures;
}

}  // namespace colmap_gcn
