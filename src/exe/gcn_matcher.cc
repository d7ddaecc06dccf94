#include "exe/gcn_matcher.h"

#include "controllers/gcn_matching.h"
#include "util/error.h"
#include "util/option_manager.h"

namespace colmap_gcn {

void AddGcnMatchingOptions(OptionManager* manager,
                           GcnMatchingOptions* options) {
  manager->AddDefaultOption("GcnMatching.pairing",
                            &options->pairing,
                            "gcn | exhaustive | imported | knn | vocab_tree");
  GcnModelPairingOptions& gcn = options->gcn;
  manager->AddDefaultOption(
      "GcnMatching.model_path",
      &gcn.model_path,
      "GCN model file (pairing=gcn); empty: default model");
  manager->AddDefaultOption("GcnMatching.k1",
                            &gcn.k1,
                            "1-hop neighbours per query; -1: model's value");
  manager->AddDefaultOption("GcnMatching.k2",
                            &gcn.k2,
                            "2-hop neighbours per 1-hop node; -1: model's");
  manager->AddDefaultOption(
      "GcnMatching.u", &gcn.u, "neighbours that make QES edges; -1: model's");
  manager->AddDefaultOption("GcnMatching.threshold",
                            &gcn.threshold,
                            "GCN score to retrieve a pair; -1: model's (0.5)");
  manager->AddDefaultOption("GcnMatching.min_pairs_per_image",
                            &gcn.min_pairs_per_image,
                            "best-scoring pairs every image keeps");
  manager->AddDefaultOption("GcnMatching.match_list_path",
                            &options->imported.match_list_path,
                            "pairs file for pairing=imported");
  manager->AddDefaultOption("GcnMatching.k",
                            &options->knn.k,
                            "neighbours per image for knn | vocab_tree");
  manager->AddDefaultOption("GcnMatching.k", &options->vocab_tree.k);
  manager->AddDefaultOption("GcnMatching.embedding_path",
                            &options->knn.descriptors.embedding_path,
                            "trained VLAD model (gcn_embedding_trainer); "
                            "empty: trained on this database");
  manager->AddDefaultOption("GcnMatching.descriptor_path",
                            &options->knn.descriptors.descriptor_path,
                            "imported global descriptors (.h5 | .npy | .txt)");
  manager->AddDefaultOption("GcnMatching.descriptor_path",
                            &gcn.descriptor_path);
  manager->AddDefaultOption("GcnMatching.vocab_tree_path",
                            &options->vocab_tree.vocab_tree_path,
                            "vocabulary tree; empty: built from this database");
  manager->AddDefaultOption("GcnMatching.num_threads",
                            &gcn.num_threads,
                            "threads for embedding and kNN (-1: all cores)");
  manager->AddDefaultOption("GcnMatching.num_threads",
                            &options->knn.num_threads);
  GcnMatchingOptions::Matching& matching = options->matching;
  manager->AddDefaultOption(
      "GcnMatching.block_size",
      &matching.block_size,
      "pairs per COLMAP matching run (each commits; resume granularity)");
  manager->AddDefaultOption("GcnMatching.pairs_path",
                            &matching.pairs_path,
                            "where the chosen pairs are written");
  manager->AddDefaultOption("GcnMatching.colmap_log_path",
                            &matching.colmap_log_path,
                            "log of COLMAP's full output");
  manager->AddDefaultOption(
      "GcnMatching.verbose", &matching.verbose, "show all of COLMAP's output");
  manager->AddPassThroughPrefix("SiftMatching.");
}

void CheckSiftMatchingArguments(const std::vector<std::string>& args) {
  const int min_num_inliers =
      IntArgument(args, "SiftMatching.min_num_inliers", 0);
  if (min_num_inliers < 0) {
    ThrowError("--SiftMatching.min_num_inliers must be >= 0 (got ",
               min_num_inliers,
               ")");
  }
}

int RunGcnMatcher(int argc, char** argv) {
  std::string database_path;
  GcnMatchingOptions options;
  OptionManager manager(
      "gcn_matcher",
      "Chooses the image pairs worth matching and matches them with COLMAP's "
      "own matcher and geometric verification.");
  manager.AddRequiredOption("database_path", &database_path);
  AddGcnMatchingOptions(&manager, &options);
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  options.colmap_args = manager.PassThroughArguments();
  manager.Check([&] { options.Check(); });
  CheckSiftMatchingArguments(options.colmap_args);
  PrintGcnMatchingReport(RunGcnMatching(database_path, options));
  return 0;
}

}  // namespace colmap_gcn
