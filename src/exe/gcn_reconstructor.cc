#include "exe/gcn_reconstructor.h"

#include <cstdio>

#include "controllers/colmap_runner.h"
#include "controllers/feature_extraction.h"
#include "controllers/gcn_matching.h"
#include "controllers/incremental_mapping.h"
#include "exe/gcn_matcher.h"
#include "scene/reconstruction.h"
#include "scene/reconstruction_stats.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {

int RunGcnReconstructor(int argc, char** argv) {
  std::string image_path;
  std::string workspace_path;
  GcnMatchingOptions matching_options;
  FeatureExtractionOptions extraction_options;
  IncrementalMappingOptions mapping_options;
  OptionManager manager(
      "gcn_reconstructor",
      "Extracts features, matches the pairs gcn_matcher selects and maps: "
      "<workspace_path>/database.db and <workspace_path>/sparse/N.");
  manager.AddRequiredOption("image_path", &image_path);
  manager.AddRequiredOption("workspace_path", &workspace_path);
  AddGcnMatchingOptions(&manager, &matching_options);
  // COLMAP's options that we set ourselves: read here, passed once.
  manager.AddDefaultOption("ImageReader.single_camera",
                           &extraction_options.single_camera,
                           "one camera for all images");
  manager.AddDefaultOption("Mapper.num_threads",
                           &mapping_options.num_threads,
                           "mapper threads; -1: all cores");
  manager.AddDefaultOption("Mapper.min_model_size",
                           &mapping_options.min_model_size,
                           "smaller models are discarded by the mapper");
  manager.AddPassThroughPrefix("SiftMatching.");
  manager.AddPassThroughPrefix("ImageReader.");
  manager.AddPassThroughPrefix("SiftExtraction.");
  manager.AddPassThroughPrefix("Mapper.");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] {
    matching_options.Check();
    CHECK_OPTION_NUM_THREADS(mapping_options.num_threads);
    CHECK_OPTION_GE(mapping_options.min_model_size, 0);
  });
  // COLMAP's own options are checked by COLMAP before anything runs.
  CheckColmapArguments(manager.PassThroughArguments());
  CheckImageFolder(image_path);
  CheckOutputFolder(matching_options.matching.colmap_log_path);
  CheckOutputFolder(matching_options.matching.pairs_path);
  CreateDirIfNotExists(workspace_path);
  const std::string database_path = JoinPaths(workspace_path, "database.db");
  const std::string sparse_path = JoinPaths(workspace_path, "sparse");
  const auto& args = manager.PassThroughArguments();

  ColmapRunnerOptions runner_options;
  runner_options.log_path = JoinPaths(workspace_path, "colmap.log");
  runner_options.verbose = matching_options.matching.verbose;
  const ColmapRunner colmap(runner_options);
  if (matching_options.matching.colmap_log_path.empty()) {
    matching_options.matching.colmap_log_path = runner_options.log_path;
  }

  LOG(INFO) << "[1/3] feature_extractor";
  extraction_options.image_path = image_path;
  extraction_options.colmap_args =
      ArgumentsWithPrefix(args, {"ImageReader.", "SiftExtraction."});
  const FeatureExtractionSummary extraction =
      ExtractFeatures(colmap, database_path, extraction_options);

  LOG(INFO) << "[2/3] gcn_matcher";
  matching_options.colmap_args = ArgumentsWithPrefix(args, {"SiftMatching."});
  const GcnMatchingReport matching =
      RunGcnMatching(database_path, matching_options);

  LOG(INFO) << "[3/3] mapper";
  if (!ListSparseModels(sparse_path).empty()) {
    ThrowError(sparse_path,
               " already holds models; use a new --workspace_path");
  }
  mapping_options.image_path = image_path;
  mapping_options.colmap_args = ArgumentsWithPrefix(args, {"Mapper."});
  const IncrementalMappingSummary mapping = RunIncrementalMapping(
      colmap, database_path, sparse_path, mapping_options);

  PrintGcnMatchingReport(matching);
  std::printf("\nextraction %.1f s, matching %.1f s, mapping %.1f s\n",
              extraction.seconds,
              matching.matching.matching_seconds,
              mapping.seconds);
  std::printf("%-28s %10s %8s %12s %10s %10s\n",
              "model",
              "registered",
              "points",
              "observations",
              "track_len",
              "reproj_px");
  for (const std::string& model_path : mapping.model_paths) {
    Reconstruction reconstruction;
    reconstruction.Read(model_path);
    const ReconstructionStatistics stats =
        ComputeReconstructionStatistics(reconstruction);
    std::printf("%-28s %5zu/%-4zu %8zu %12zu %10.2f %10.3f\n",
                model_path.c_str(),
                stats.num_registered_images,
                matching.num_images,
                stats.num_points3D,
                stats.num_observations,
                stats.mean_track_length,
                stats.mean_reprojection_error);
  }
  if (mapping.model_paths.empty()) {
    std::printf("(the mapper produced no model)\n");
    return 1;
  }
  return 0;
}

}  // namespace colmap_gcn
