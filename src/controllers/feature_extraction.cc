#include "controllers/feature_extraction.h"

#include <filesystem>
#include <regex>

#include "scene/database.h"
#include "scene/database_copy.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

// Images COLMAP 3.8 reports as extracted: one "Features: <n>" line each.
size_t CountReportedImages(const std::string& output) {
  static const std::regex kFeatures(R"(^\s*Features:\s+\d+\s*$)");
  size_t count = 0;
  for (const std::string& line : StringSplit(output, "\n")) {
    if (std::regex_search(line, kFeatures)) ++count;
  }
  return count;
}

// What COLMAP was meant to write, checked in the database rather than
// trusted from its exit code: keypoints and descriptors for every image, at
// least as many images with both as it reported extracting.
void VerifyExtraction(const std::string& database_path,
                      const std::string& output) {
  const Database database(database_path);
  const std::vector<DatabaseImage> missing =
      database.ReadImagesWithoutFeatures();
  const size_t num_images = database.NumImages();
  if (!missing.empty()) {
    ThrowError("colmap feature_extractor exited 0 but ",
               missing.size(),
               " of the ",
               num_images,
               " images in ",
               database_path,
               " have no keypoints or descriptors (the first: ",
               missing.front().name,
               "); run again to extract them");
  }
  const size_t num_reported = CountReportedImages(output);
  if (num_images < num_reported) {
    ThrowError("colmap feature_extractor reported ",
               num_reported,
               " images extracted but ",
               database_path,
               " holds ",
               num_images,
               "; run again to extract the others");
  }
}

}  // namespace

void FeatureExtractionOptions::Check() const {
  CHECK_OPTION(image_path, !image_path.empty(), "name an image folder");
  CHECK_OPTION_GE(min_num_images, 0);
}

FeatureExtractionSummary ExtractFeatures(
    const ColmapRunner& colmap,
    const std::string& database_path,
    const FeatureExtractionOptions& options) {
  options.Check();
  std::string output_path = database_path;
  if (options.replace_database) {
    output_path = database_path + ".partial";
    RemoveDatabaseFiles(output_path);
    RemoveDatabaseFiles(database_path);
  }
  std::vector<std::string> args = {
      "--database_path", output_path, "--image_path", options.image_path};
  if (!options.image_list_path.empty()) {
    args.push_back("--image_list_path");
    args.push_back(options.image_list_path);
  }
  if (options.single_camera) {
    args.push_back("--ImageReader.single_camera");
    args.push_back("1");
  }
  args.insert(
      args.end(), options.colmap_args.begin(), options.colmap_args.end());
  FeatureExtractionSummary summary;
  const Timer timer;
  const bool existed = ExistsFile(output_path);
  try {
    VerifyExtraction(output_path, colmap.Run("feature_extractor", args));
  } catch (const Error&) {
    // A scratch database is not resumed, and one this run created holds
    // nothing to resume (COLMAP rolls a failed extraction back, or fails
    // before its tables exist): the next run starts over. A database that
    // existed keeps what COLMAP committed into it.
    if (options.replace_database || !existed) {
      RemoveDatabaseFiles(output_path);
    }
    throw;
  }
  summary.seconds = timer.ElapsedSeconds();
  if (options.replace_database) {
    // Our check above read it: its empty side files must not stay behind
    // under the scratch name once the database is renamed.
    RemoveEmptySqliteSideFiles(output_path);
    std::error_code ec;
    std::filesystem::rename(output_path, database_path, ec);
    if (ec) ThrowError("cannot rename ", output_path, ": ", ec.message());
  }
  summary.num_images = Database(database_path).NumImages();
  RemoveEmptySqliteSideFiles(database_path);
  if (summary.num_images < static_cast<size_t>(options.min_num_images)) {
    ThrowError("colmap feature_extractor read ",
               summary.num_images,
               " image(s) from ",
               options.image_path,
               "; at least ",
               options.min_num_images,
               " readable images are needed");
  }
  return summary;
}

void CheckImageFolder(const std::string& path) {
  if (!ExistsDir(path)) {
    ThrowError("image folder not found: ", path);
  }
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(path, ec);
       !ec && it != std::filesystem::recursive_directory_iterator();
       it.increment(ec)) {
    if (it->is_regular_file(ec)) return;
  }
  ThrowError("image folder ", path, " holds no files");
}

}  // namespace colmap_gcn
