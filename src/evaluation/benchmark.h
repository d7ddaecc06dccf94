#pragma once

#include <string>
#include <vector>

#include "controllers/gcn_matching.h"
#include "evaluation/alignment.h"
#include "evaluation/labels.h"
#include "evaluation/pose_pair_filter.h"
#include "evaluation/results.h"

namespace colmap_gcn {

struct BenchmarkOptions {
  // Comma list of scene folders or synth:<family>:<n>[:seed].
  std::string datasets = "";

  // Comma list of methods (see method.h), run in this order on each scene.
  std::string methods = "exhaustive,knn:25,vocab_tree:25,gcn,oracle";

  // Everything goes here: <output_path>/<scene>/..., report.md,
  // results.csv, results.json, figures/.
  std::string output_path = "";

  PairLabelOptions labels;
  PoseErrorOptions pose;

  // Which pairs the labels of scenes with GT cameras are matched on. Off
  // by default (every pair, the exhaustive method's matches); when enabled
  // only the pairs the pose rule keeps are matched, in labels/matching/,
  // and a skipped pair keeps what the triangulated tracks give it (in
  // practice CT = 0: negative).
  PosePairFilterOptions label_pair_filter;

  // One camera for all of a scene's images: 1 yes, 0 no, -1 as its dataset
  // says (--ImageReader.single_camera).
  int single_camera = -1;

  // Mapper threads; 1 makes mapper runs repeatable (COLMAP's own advice).
  int mapper_num_threads = 1;

  // Mapper models with fewer registered images are discarded. COLMAP
  // 3.8's default 10 (bounded by 0.8 x the images) discards even the first
  // model of a small scene that registers fewer; 3 keeps partial models in
  // the tables, but also keeps poor starts on large scenes
  // (docs/benchmarks.md): pass 10 there to map as users do.
  int mapper_min_model_size = 3;

  // results.json of a benchmark that ran a merged collection's scenes
  // alone with the exhaustive method
  // (scripts/research/collection_benchmark.sh): each scene's registered
  // images there are what the collection's methods are compared against.
  // "": no comparison.
  std::string alone_results_path = "";

  // Passed to COLMAP: feature_extractor (--ImageReader.*,
  // --SiftExtraction.*), matches_importer (--SiftMatching.*), mapper
  // (--Mapper.*).
  std::vector<std::string> extraction_args;
  std::vector<std::string> matching_args;
  std::vector<std::string> mapper_args;

  // Every method's generator options (e.g. --GcnMatching.model_path for
  // gcn); pairing and k come from the method, the oracle's options are the
  // defaults.
  GcnMatchingOptions gcn_matching;

  // Show all of COLMAP's output.
  bool verbose = false;

  // gcn_benchmark exits 0 even when scenes or methods failed (the summary
  // is printed either way).
  bool keep_going = false;

  // Real COLMAP binary ("" finds it, see ColmapRunner).
  std::string colmap_exe = "";

  // Recorded in the report.
  std::string command = "";

  // How every method's pairs (and the labels' pose-filtered pairs) are
  // matched: matching_args and gcn_matching's min_num_inliers.
  PairMatchingOptions MatchingOptions() const;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// Runs every method on every scene (extraction once per scene, methods
// interleaved per scene so their times are comparable), caching per scene
// and method so an interrupted run resumes, evaluates against the labels
// and writes the report (see report.h). A method that cannot be built is
// "unavailable", one whose COLMAP run fails is "failed"; neither stops the
// run. Throws Error on invalid options or an unusable dataset.
// Checks the options, the methods and every dataset (CheckDataset) before
// any work.
BenchmarkResults RunBenchmark(const BenchmarkOptions& options);

// One line per failed scene ("<scene>: <why>") and per method that did not
// finish in a scene that did ("<scene>/<method> failed: <why>").
std::vector<std::string> BenchmarkFailures(const BenchmarkResults& results);

}  // namespace colmap_gcn
