#include "exe/gcn_vocab_tree_builder.h"

#include <iostream>
#include <string>
#include <vector>

#include "controllers/colmap_runner.h"
#include "controllers/gcn_matching.h"
#include "controllers/vocab_tree_pairing.h"
#include "scene/database_copy.h"
#include "util/error.h"
#include "util/option_manager.h"
#include "util/string.h"
#include "util/timer.h"

namespace colmap_gcn {

int RunGcnVocabTreeBuilder(int argc, char** argv) {
  std::string database_paths;
  std::string output_path;
  VocabTreeBuildOptions options;
  ColmapRunnerOptions runner_options;
  OptionManager manager(
      "gcn_vocab_tree_builder",
      "Builds a vocabulary tree for gcn_matcher --GcnMatching.pairing "
      "vocab_tree with COLMAP's vocab_tree_builder from one or more "
      "databases (no tree can be downloaded).");
  manager.AddRequiredOption(
      "database_paths", &database_paths, "comma-separated databases");
  manager.AddRequiredOption("output_path", &output_path, "tree file");
  manager.AddDefaultOption("num_visual_words",
                           &options.num_visual_words,
                           "0: about one per 50 descriptors, power of 2");
  manager.AddDefaultOption("branching", &options.branching);
  manager.AddDefaultOption("num_iterations", &options.num_iterations);
  manager.AddDefaultOption("colmap_log_path",
                           &runner_options.log_path,
                           "log of COLMAP's full output");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] { options.Check(); });
  CheckOutputFolder(runner_options.log_path);
  const std::vector<std::string> paths = SplitCommaList(database_paths);
  if (paths.empty()) {
    ThrowError("--database_paths lists no database");
  }
  for (const std::string& path : paths) RecoverHotJournal(path);
  const Timer timer;
  BuildVocabTree(ColmapRunner(runner_options), paths, output_path, options);
  std::cout << "vocabulary tree from " << paths.size()
            << " database(s) built in " << timer.ElapsedSeconds()
            << " s; written to " << output_path << "\n";
  return 0;
}

}  // namespace colmap_gcn
