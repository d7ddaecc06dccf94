#include "controllers/incremental_mapping.h"

#include <filesystem>

#include "scene/reconstruction_stats.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/timer.h"

namespace colmap_gcn {

void IncrementalMappingOptions::Check() const {
  CHECK_OPTION(image_path, !image_path.empty(), "name an image folder");
  CHECK_OPTION_NUM_THREADS(num_threads);
  CHECK_OPTION_GE(min_model_size, 0);
}

IncrementalMappingSummary RunIncrementalMapping(
    const ColmapRunner& colmap,
    const std::string& database_path,
    const std::string& output_path,
    const IncrementalMappingOptions& options) {
  options.Check();
  if (options.replace_models) {
    std::error_code ec;
    std::filesystem::remove_all(output_path, ec);
  }
  CreateDirIfNotExists(output_path);
  if (!ListSparseModels(output_path).empty()) {
    ThrowError(output_path, " already holds models");
  }
  std::vector<std::string> args = {"--database_path",
                                   database_path,
                                   "--image_path",
                                   options.image_path,
                                   "--output_path",
                                   output_path};
  if (!HasArgument(options.colmap_args, "Mapper.num_threads")) {
    args.push_back("--Mapper.num_threads");
    args.push_back(std::to_string(options.num_threads));
  }
  if (!HasArgument(options.colmap_args, "Mapper.min_model_size")) {
    args.push_back("--Mapper.min_model_size");
    args.push_back(std::to_string(options.min_model_size));
  }
  args.insert(
      args.end(), options.colmap_args.begin(), options.colmap_args.end());
  IncrementalMappingSummary summary;
  const Timer timer;
  colmap.Run("mapper", args);
  summary.seconds = timer.ElapsedSeconds();
  summary.model_paths = ListSparseModels(output_path);
  return summary;
}

}  // namespace colmap_gcn
