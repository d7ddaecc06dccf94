#pragma once

#include <string>
#include <vector>

#include "controllers/colmap_runner.h"

namespace colmap_gcn {

// `colmap feature_extractor` as gcn_reconstructor and gcn_benchmark run it.
struct FeatureExtractionOptions {
  // The images COLMAP reads (its reader walks the folder recursively).
  std::string image_path = "";

  // Only the images this file lists (--image_list_path); empty: every image
  // under image_path.
  std::string image_list_path = "";

  // One camera for all images (--ImageReader.single_camera 1); commands
  // bind the user's --ImageReader.single_camera here, never in colmap_args.
  bool single_camera = false;

  // Extract into "<database_path>.partial" and rename it over database_path
  // only once COLMAP finished, so an interrupted extraction leaves no
  // half-filled database to trust; an existing database is replaced. Off:
  // COLMAP writes database_path in place, adding the images it lacks.
  bool replace_database = false;

  // A database with fewer images after extraction is an error (0: any).
  int min_num_images = 2;

  // --ImageReader.* and --SiftExtraction.* arguments, passed after ours.
  std::vector<std::string> colmap_args;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

struct FeatureExtractionSummary {
  size_t num_images = 0;  // in the database afterwards
  double seconds = 0;     // wall time of COLMAP's extraction
};

// Runs `colmap feature_extractor` into database_path. Throws Error when
// COLMAP fails or the database holds fewer than options.min_num_images
// images.
FeatureExtractionSummary ExtractFeatures(
    const ColmapRunner& colmap,
    const std::string& database_path,
    const FeatureExtractionOptions& options);

// Throws Error unless path is a folder holding at least one file: COLMAP's
// reader skips what it cannot decode, but a folder without a single file
// cannot give any image.
void CheckImageFolder(const std::string& path);

}  // namespace colmap_gcn
