#include "controllers/incremental_mapping.h"

#include <filesystem>

#include "scene/reconstruction.h"
#include "scene/reconstruction_stats.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

// Every model the mapper wrote must read back: COLMAP 3.8 writes its model
// files unchecked, so a full disk leaves truncated files behind exit 0.
void VerifyModels(const std::vector<std::string>& model_paths) {
  for (const std::string& model_path : model_paths) {
    try {
      Reconstruction reconstruction;
      reconstruction.Read(model_path);
    } catch (const Error& error) {
      ThrowError("colmap mapper exited 0 but wrote an unreadable model (",
                 error.what(),
                 ")");
    }
  }
}

}  // namespace

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
  // The mapper writes into a scratch folder whose models move into
  // output_path only once they all read back, so an interrupted or failed
  // run leaves no model to be taken for a result, and the next run starts
  // clean.
  const std::string scratch_path = output_path + ".partial";
  {
    std::error_code ec;
    std::filesystem::remove_all(scratch_path, ec);
  }
  CreateDirIfNotExists(scratch_path);
  std::vector<std::string> args = {"--database_path",
                                   database_path,
                                   "--image_path",
                                   options.image_path,
                                   "--output_path",
                                   scratch_path};
  args.push_back("--Mapper.num_threads");
  args.push_back(std::to_string(options.num_threads));
  args.push_back("--Mapper.min_model_size");
  args.push_back(std::to_string(options.min_model_size));
  args.insert(
      args.end(), options.colmap_args.begin(), options.colmap_args.end());
  IncrementalMappingSummary summary;
  const Timer timer;
  try {
    colmap.Run("mapper", args);
    VerifyModels(ListSparseModels(scratch_path));
  } catch (const Error&) {
    std::error_code ec;
    std::filesystem::remove_all(scratch_path, ec);
    throw;
  }
  summary.seconds = timer.ElapsedSeconds();
  for (const std::string& model_path : ListSparseModels(scratch_path)) {
    const std::filesystem::path model(model_path);
    std::error_code ec;
    std::filesystem::rename(
        model, std::filesystem::path(output_path) / model.filename(), ec);
    if (ec) {
      ThrowError("cannot move ",
                 model_path,
                 " into ",
                 output_path,
                 ": ",
                 ec.message());
    }
  }
  std::error_code ec;
  std::filesystem::remove_all(scratch_path, ec);
  summary.model_paths = ListSparseModels(output_path);
  return summary;
}

}  // namespace colmap_gcn
