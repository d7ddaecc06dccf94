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
  manager->AddDefaultOption(
      "GcnMatching.model_path",
      &options->model_path,
      "GCN model file (pairing=gcn); empty: default model");
  manager->AddDefaultOption("GcnMatching.k1",
                            &options->k1,
                            "1-hop neighbours per query; -1: model's value");
  manager->AddDefaultOption("GcnMatching.k2",
                            &options->k2,
                            "2-hop neighbours per 1-hop node; -1: model's");
  manager->AddDefaultOption("GcnMatching.u",
                            &options->u,
                            "neighbours that make QES edges; -1: model's");
  manager->AddDefaultOption("GcnMatching.threshold",
                            &options->threshold,
                            "GCN score to retrieve a pair; -1: model's (0.5)");
  manager->AddDefaultOption("GcnMatching.min_pairs_per_image",
                            &options->min_pairs_per_image,
                            "best-scoring pairs every image keeps");
  manager->AddDefaultOption("GcnMatching.match_list_path",
                            &options->match_list_path,
                            "pairs file for pairing=imported");
  manager->AddDefaultOption("GcnMatching.k",
                            &options->k,
                            "neighbours per image for knn | vocab_tree");
  manager->AddDefaultOption("GcnMatching.embedding_path",
                            &options->embedding_path,
                            "trained VLAD model (gcn_embedding_trainer); "
                            "empty: trained on this database");
  manager->AddDefaultOption("GcnMatching.descriptor_path",
                            &options->descriptor_path,
                            "imported global descriptors (.h5 | .npy | .txt)");
  manager->AddDefaultOption(
      "GcnMatching.embedding",
      &options->embedding,
      "vlad | onnx | vlad+onnx | imported; empty: the model's (gcn), vlad "
      "(knn)");
  manager->AddDefaultOption("GcnMatching.onnx_path",
                            &options->onnx_path,
                            "ONNX network for embedding=onnx (OpenCV DNN)");
  manager->AddDefaultOption(
      "GcnMatching.image_path",
      &options->image_path,
      "folder of the images (as given to feature_extractor); needed by onnx");
  manager->AddDefaultOption("GcnMatching.onnx_max_image_size",
                            &options->onnx.max_image_size,
                            "CNN input long side; -1: the model's (knn: 512)");
  manager->AddDefaultOption("GcnMatching.onnx_size_multiple",
                            &options->onnx.size_multiple,
                            "CNN input sides multiple of; -1: model's (32)");
  manager->AddDefaultOption("GcnMatching.onnx_scale",
                            &options->onnx.scale,
                            "(pixel - mean) * scale; -1: model's (1/127.5)");
  manager->AddDefaultOption("GcnMatching.onnx_mean",
                            &options->onnx.mean,
                            "subtracted from pixels; -1: model's (127.5)");
  manager->AddDefaultOption("GcnMatching.onnx_swap_rb",
                            &options->onnx.swap_rb,
                            "1: RGB input, 0: BGR; -1: model's (1)");
  manager->AddDefaultOption("GcnMatching.onnx_gem_p",
                            &options->onnx.gem_p,
                            "GeM pooling exponent; -1: model's (3)");
  manager->AddDefaultOption("GcnMatching.onnx_center",
                            &options->onnx.center,
                            "1: subtract the collection mean; -1: model's (1)");
  manager->AddDefaultOption("GcnMatching.onnx_batch_size",
                            &options->onnx_batch_size,
                            "images per CNN forward pass");
  manager->AddDefaultOption("GcnMatching.vocab_tree_path",
                            &options->vocab_tree_path,
                            "vocabulary tree; empty: built from this database");
  manager->AddDefaultOption("GcnMatching.num_threads",
                            &options->num_threads,
                            "threads for embedding and kNN (-1: all cores)");
  manager->AddDefaultOption(
      "GcnMatching.block_size",
      &options->block_size,
      "pairs per COLMAP matching run (each commits; resume granularity)");
  manager->AddDefaultOption("GcnMatching.pairs_path",
                            &options->pairs_path,
                            "where the chosen pairs are written");
  manager->AddDefaultOption("GcnMatching.colmap_log_path",
                            &options->colmap_log_path,
                            "log of COLMAP's full output");
  manager->AddDefaultOption(
      "GcnMatching.verbose", &options->verbose, "show all of COLMAP's output");
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
  manager.Check([&] { options.Check(); });
  CheckSiftMatchingArguments(manager.PassThroughArguments());
  PrintGcnMatchingReport(
      RunGcnMatching(database_path, options, manager.PassThroughArguments()));
  return 0;
}

}  // namespace colmap_gcn
