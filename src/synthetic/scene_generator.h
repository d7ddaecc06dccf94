#pragma once

#include <string>

namespace colmap_gcn {

// Options of the synthetic scene generator (`colmap gcn_synth`).
struct SyntheticSceneOptions {
  // Scene family: "ordinary", "repetitive", "symmetric", "twin_print" or
  // "twin_objects" (src/synthetic/scene_families.h).
  std::string family = "ordinary";
  // Images of the scene (named synth_0000.jpg, ...).
  int num_images = 40;
  // Unrelated images, each from its own random little scene (named
  // distractor_0000.jpg, ...), overlapping nothing.
  int num_distractors = 0;
  int width = 640;
  int height = 480;
  // Focal length in pixels = focal_length_factor * max(width, height).
  double focal_length_factor = 1.0;
  int seed = 0;
  // Threads for textures and rendering; -1: all hardware threads. The
  // output does not depend on it.
  int num_threads = -1;
  // Optional folder of texture images replacing the procedural "random"
  // textures (window tiles and roofs stay procedural).
  std::string texture_dir;
  // Surface points sampled uniformly per area; the unit of overlap.
  int num_surface_samples = 60000;
  // Symmetric family: number of identical sides.
  int symmetric_sides = 8;
  // A sample is visible only if the cosine between its normal and the ray
  // to the camera exceeds this (rejects grazing views).
  double min_view_cosine = 0.1;
  int jpeg_quality = 95;
  // Per-image exposure, blur and noise variation.
  bool photometric_variation = true;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

struct SyntheticSceneSummary {
  int num_images = 0;
  int num_distractors = 0;
  size_t num_points3D = 0;
  size_t num_observations = 0;
  size_t num_pairs = 0;
  // Unordered pairs of scene images with min(overlap12, overlap21) >= 0.3.
  size_t num_pairs_overlap_03 = 0;
  // Largest distance between two camera centres (the scene size used for
  // relative errors).
  double scene_size = 0.0;
  double seconds = 0.0;
};

// Renders the scene into <output_path>/images and writes the ground truth
// into <output_path>/gt: a COLMAP text model (cameras.txt, images.txt,
// points3D.txt; PINHOLE camera, world-to-camera poses, sampled surface points
// with their visibility tracks), pair_overlap.csv (see pair_overlap.h),
// distractors.txt (distractor image names, one per line) and scene.txt
// (key value lines: family, seed, sizes, scene_size). Deterministic for the
// options regardless of num_threads. Throws Error on invalid options or I/O
// failure.
SyntheticSceneSummary GenerateSyntheticScene(
    const SyntheticSceneOptions& options, const std::string& output_path);

// "synth_0007.jpg", "distractor_0002.jpg".
std::string SyntheticImageName(int index);
std::string DistractorImageName(int index);

}  // namespace colmap_gcn
