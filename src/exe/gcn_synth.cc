#include "exe/gcn_synth.h"

#include <cstdio>
#include <iostream>
#include <string>

#include "synthetic/scene_generator.h"
#include "util/error.h"
#include "util/option_manager.h"

namespace colmap_gcn {

int RunGcnSynth(int argc, char** argv) {
  std::string output_path;
  SyntheticSceneOptions options;
  OptionManager manager(
      "gcn_synth",
      "Renders a synthetic scene with exact ground truth: <output_path>/images "
      "and <output_path>/gt (COLMAP text model, pair_overlap.csv, "
      "distractors.txt, scene.txt).");
  manager.AddRequiredOption("output_path", &output_path);
  manager.AddDefaultOption("GcnSynth.family",
                           &options.family,
                           "ordinary, repetitive, symmetric, twin_print or "
                           "twin_objects");
  manager.AddDefaultOption("GcnSynth.num_images", &options.num_images);
  manager.AddDefaultOption("GcnSynth.num_distractors",
                           &options.num_distractors,
                           "unrelated images overlapping nothing");
  manager.AddDefaultOption("GcnSynth.width", &options.width);
  manager.AddDefaultOption("GcnSynth.height", &options.height);
  manager.AddDefaultOption("GcnSynth.focal_length_factor",
                           &options.focal_length_factor,
                           "focal length / max(width, height)");
  manager.AddDefaultOption("GcnSynth.seed", &options.seed);
  manager.AddDefaultOption("GcnSynth.num_threads",
                           &options.num_threads,
                           "-1: all cores; the output does not depend on it");
  manager.AddDefaultOption("GcnSynth.texture_dir",
                           &options.texture_dir,
                           "optional folder of texture images");
  manager.AddDefaultOption("GcnSynth.num_surface_samples",
                           &options.num_surface_samples);
  manager.AddDefaultOption("GcnSynth.symmetric_sides",
                           &options.symmetric_sides);
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] { options.Check(); });
  const SyntheticSceneSummary summary =
      GenerateSyntheticScene(options, output_path);
  std::printf(
      "gcn_synth: %s scene, %d images + %d distractors, %zu points3D, "
      "%zu observations, %zu pairs (%zu with overlap >= 0.3), scene size "
      "%.2f, %.2f s\n",
      options.family.c_str(),
      summary.num_images,
      summary.num_distractors,
      summary.num_points3D,
      summary.num_observations,
      summary.num_pairs,
      summary.num_pairs_overlap_03,
      summary.scene_size,
      summary.seconds);
  std::fflush(stdout);
  return 0;
}

}  // namespace colmap_gcn
