#include "exe/gcn_reconstructor.h"

#include <cstdio>
#include <filesystem>

#include "controllers/colmap_runner.h"
#include "controllers/gcn_matching.h"
#include "exe/gcn_matcher.h"
#include "scene/database.h"
#include "scene/reconstruction.h"
#include "scene/reconstruction_stats.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/option_manager.h"
#include "util/string.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

// COLMAP's image reader walks the folder recursively and skips what it
// cannot decode; a folder without a single file cannot give any image.
bool HoldsAnyFile(const std::string& folder) {
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(folder, ec);
       !ec && it != std::filesystem::recursive_directory_iterator();
       it.increment(ec)) {
    if (it->is_regular_file(ec)) return true;
  }
  return false;
}

}  // namespace

int RunGcnReconstructor(int argc, char** argv) {
  std::string image_path;
  std::string workspace_path;
  GcnMatchingOptions matching_options;
  OptionManager manager(
      "gcn_reconstructor",
      "Extracts features, matches the pairs gcn_matcher selects and maps: "
      "<workspace_path>/database.db and <workspace_path>/sparse/N.");
  manager.AddRequiredOption("image_path", &image_path);
  manager.AddRequiredOption("workspace_path", &workspace_path);
  AddGcnMatchingOptions(&manager, &matching_options);
  manager.AddPassThroughPrefix("SiftMatching.");
  manager.AddPassThroughPrefix("ImageReader.");
  manager.AddPassThroughPrefix("SiftExtraction.");
  manager.AddPassThroughPrefix("Mapper.");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] { matching_options.Check(); });
  CheckSiftMatchingArguments(manager.PassThroughArguments());
  if (!ExistsDir(image_path)) {
    ThrowError("image folder not found: ", image_path);
  }
  if (!HoldsAnyFile(image_path)) {
    ThrowError("image folder ", image_path, " holds no files");
  }
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
  Timer timer;
  std::vector<std::string> extraction_args = {
      "--database_path", database_path, "--image_path", image_path};
  const auto extraction_options =
      ArgumentsWithPrefix(args, {"ImageReader.", "SiftExtraction."});
  extraction_args.insert(extraction_args.end(),
                         extraction_options.begin(),
                         extraction_options.end());
  colmap.Run("feature_extractor", extraction_args);
  const double extraction_seconds = timer.ElapsedSeconds();
  {
    const Database database(database_path);
    if (database.NumImages() < 2) {
      ThrowError("colmap feature_extractor read ",
                 database.NumImages(),
                 " image(s) from ",
                 image_path,
                 "; at least 2 readable images are needed");
    }
  }

  LOG(INFO) << "[2/3] gcn_matcher";
  matching_options.colmap_args = ArgumentsWithPrefix(args, {"SiftMatching."});
  const GcnMatchingReport matching =
      RunGcnMatching(database_path, matching_options);

  LOG(INFO) << "[3/3] mapper";
  CreateDirIfNotExists(sparse_path);
  if (!ListSparseModels(sparse_path).empty()) {
    ThrowError(sparse_path,
               " already holds models; use a new --workspace_path");
  }
  timer.Restart();
  std::vector<std::string> mapper_args = {"--database_path",
                                          database_path,
                                          "--image_path",
                                          image_path,
                                          "--output_path",
                                          sparse_path};
  const auto mapper_options = ArgumentsWithPrefix(args, {"Mapper."});
  mapper_args.insert(
      mapper_args.end(), mapper_options.begin(), mapper_options.end());
  colmap.Run("mapper", mapper_args);
  const double mapping_seconds = timer.ElapsedSeconds();

  PrintGcnMatchingReport(matching);
  const std::vector<std::string> models = ListSparseModels(sparse_path);
  std::printf("\nextraction %.1f s, matching %.1f s, mapping %.1f s\n",
              extraction_seconds,
              matching.matching.matching_seconds,
              mapping_seconds);
  std::printf("%-28s %10s %8s %12s %10s %10s\n",
              "model",
              "registered",
              "points",
              "observations",
              "track_len",
              "reproj_px");
  for (const std::string& model_path : models) {
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
  if (models.empty()) {
    std::printf("(the mapper produced no model)\n");
    return 1;
  }
  return 0;
}

}  // namespace colmap_gcn
