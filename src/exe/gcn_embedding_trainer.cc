#include "exe/gcn_embedding_trainer.h"

#include <iostream>
#include <string>
#include <vector>

#include "retrieval/vlad.h"
#include "scene/database_copy.h"
#include "util/error.h"
#include "util/option_manager.h"
#include "util/string.h"
#include "util/timer.h"

namespace colmap_gcn {

int RunGcnEmbeddingTrainer(int argc, char** argv) {
  std::string database_paths;
  std::string output_path;
  VladOptions options;
  OptionManager manager(
      "gcn_embedding_trainer",
      "Trains the VLAD embedding (RootSIFT codebook + PCA-whitening) used by "
      "gcn_matcher --GcnMatching.embedding_path on the features of one or "
      "more COLMAP databases.");
  manager.AddRequiredOption(
      "database_paths", &database_paths, "comma-separated databases");
  manager.AddRequiredOption("output_path", &output_path, "model file");
  manager.AddDefaultOption(
      "GcnEmbedding.num_words", &options.num_words, "k-means visual words");
  manager.AddDefaultOption(
      "GcnEmbedding.dim", &options.dim, "output dimension (<= images - 1)");
  manager.AddDefaultOption("GcnEmbedding.shrinkage",
                           &options.shrinkage,
                           "whitening shrinkage (0: full whitening)");
  manager.AddDefaultOption("GcnEmbedding.max_training_descriptors",
                           &options.max_training_descriptors,
                           "descriptors sampled for k-means");
  manager.AddDefaultOption("GcnEmbedding.max_pca_images",
                           &options.max_pca_images,
                           "images sampled for PCA");
  manager.AddDefaultOption("GcnEmbedding.kmeans_iterations",
                           &options.kmeans_iterations);
  manager.AddDefaultOption("GcnEmbedding.seed", &options.seed);
  manager.AddDefaultOption("GcnEmbedding.num_threads",
                           &options.num_threads,
                           "-1: all cores (results do not depend on it)");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] { options.Check(); });
  const std::vector<std::string> paths = SplitCommaList(database_paths);
  if (paths.empty()) {
    ThrowError("--database_paths lists no database");
  }
  for (const std::string& path : paths) RecoverHotJournal(path);
  const Timer timer;
  const VladEmbedding embedding = TrainVladEmbedding(paths, options);
  embedding.Write(output_path);
  std::cout << "VLAD embedding: " << embedding.NumWords() << " words, "
            << embedding.OutputDim() << " dimensions, trained on "
            << paths.size() << " database(s) in " << timer.ElapsedSeconds()
            << " s; written to " << output_path << "\n";
  return 0;
}

}  // namespace colmap_gcn
