#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "synthetic/camera.h"
#include "synthetic/scene.h"

namespace colmap_gcn {

// A scene (geometry and texture specs, textures not yet generated) with the
// cameras that view it.
struct SyntheticWorld {
  Scene scene;
  std::vector<PinholeCamera> cameras;
  // Centre of the main structure (cameras look at it).
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  // Symmetric family: the structure is invariant under rotation about the
  // z axis by 2 pi / num_symmetric_sides (except the details). 0 otherwise.
  int num_symmetric_sides = 0;
};

struct WorldParams {
  int num_images = 40;
  int width = 640;
  int height = 480;
  double focal_length = 640.0;
  uint64_t seed = 0;
  // Texture sizes are multiplied by this (texel density follows the image
  // resolution: 1 for 640-pixel-wide images).
  double texture_scale = 1.0;
  // > 0: "random" textures come from these many user images (cycled).
  int num_user_textures = 0;
  // Symmetric family: number of identical sides.
  int symmetric_sides = 8;
  // Symmetric family: add the few unique details that break the symmetry.
  bool add_details = true;
};

// A non-repetitive group of buildings (main block, annex, tower, crates),
// every face with its own texture; cameras orbit it.
SyntheticWorld BuildOrdinaryWorld(const WorldParams& params);

// A block whose four facades are tiled with one window texture (identical
// windows everywhere) on a unique ground; cameras orbit it closely.
SyntheticWorld BuildRepetitiveWorld(const WorldParams& params);

// A round temple (terraces, three tiers of walls and roofs) with
// params.symmetric_sides identical sides, on a ground and inside a
// background ring that share the same symmetry, plus a few unique details;
// cameras orbit it.
SyntheticWorld BuildSymmetricWorld(const WorldParams& params);

// An object with one print on its front and back and plain ends (a
// 180-degree turn maps it onto itself, like a mug printed on both sides)
// inside a room whose walls are all different; cameras orbit it, so front
// and back views look alike except for the room behind the object.
SyntheticWorld BuildTwinPrintWorld(const WorldParams& params);

// Two identical objects (same shape, same textures, same orientation) side
// by side on a table in a room whose walls are all different; the cameras
// sweep an arc close in front of the table, the first half looking at the
// first copy and the second half at the second, so that views of different
// copies from similar angles look alike (like the books and cup-desk scenes
// of Roberts et al.).
SyntheticWorld BuildTwinObjectsWorld(const WorldParams& params);

// An unrelated little scene (own ground and boxes, no background ring) seen
// by params.num_images cameras; used for distractor images.
SyntheticWorld BuildDistractorWorld(const WorldParams& params);

}  // namespace colmap_gcn
