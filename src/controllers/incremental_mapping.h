#pragma once

#include <string>
#include <vector>

#include "controllers/colmap_runner.h"

namespace colmap_gcn {

// `colmap mapper` as gcn_reconstructor and gcn_benchmark run it. The
// defaults are COLMAP 3.8's own.
struct IncrementalMappingOptions {
  // The images the database was extracted from.
  std::string image_path = "";

  // --Mapper.num_threads; -1: all cores. One thread makes mapper runs
  // repeatable.
  int num_threads = -1;

  // --Mapper.min_model_size: models with fewer registered images are
  // discarded.
  int min_model_size = 10;

  // Remove the output folder's models first (a rerun replaces them). Off:
  // an output folder that already holds models is refused, since COLMAP
  // would number the new models after them.
  bool replace_models = false;

  // The other --Mapper.* arguments, passed after ours (never the two above,
  // which the command binds to these fields).
  std::vector<std::string> colmap_args;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

struct IncrementalMappingSummary {
  std::vector<std::string> model_paths;  // output_path/0, /1, ... in order
  double seconds = 0;                    // wall time of COLMAP's mapper
};

// Runs `colmap mapper` on database_path into output_path (created if
// missing). Throws Error when output_path holds models (unless
// replace_models) or when COLMAP fails; COLMAP 3.8's mapper also fails when
// it builds no model (ListSparseModels(output_path) then is empty).
IncrementalMappingSummary RunIncrementalMapping(
    const ColmapRunner& colmap,
    const std::string& database_path,
    const std::string& output_path,
    const IncrementalMappingOptions& options);

}  // namespace colmap_gcn
