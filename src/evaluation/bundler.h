#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "scene/reconstruction.h"

namespace colmap_gcn {

// Bundler v0.3 (bundle.out), the reference format of the 1DSfM dataset.
// Cameras look down -z with y up; points' view-list coordinates are
// relative to the image centre with y up.
struct BundlerCamera {
  double focal_length = 0;  // 0: not registered
  double k1 = 0;
  double k2 = 0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // world-to-camera
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  bool IsRegistered() const { return focal_length > 0; }
};

struct BundlerView {
  int camera_idx = -1;
  int key_idx = -1;
  double x = 0;
  double y = 0;
};

struct BundlerPoint {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  Eigen::Vector3i color = Eigen::Vector3i::Zero();
  std::vector<BundlerView> views;
};

struct BundlerFile {
  std::vector<BundlerCamera> cameras;
  std::vector<BundlerPoint> points;
};

// Throws Error naming the file (and line) on malformed input.
BundlerFile ReadBundlerFile(const std::string& path);

// Converts to a COLMAP model. Camera i is image_names[i] with image size
// image_sizes[i] (width, height). Registered cameras become RADIAL cameras
// (f, cx, cy, k1, k2) with the principal point at the image centre; poses
// are flipped to COLMAP's convention (x right, y down, looking down +z):
// R_colmap = diag(1,-1,-1) R, t_colmap = diag(1,-1,-1) t. Unregistered
// cameras (f = 0) are left out, as are their observations. Point
// observations become points2D at (cx + x, cy - y). Image and camera ids
// are i + 1.
Reconstruction BundlerToReconstruction(
    const BundlerFile& bundle,
    const std::vector<std::string>& image_names,
    const std::vector<std::pair<int, int>>& image_sizes);

// The inverse for models with SIMPLE_PINHOLE, PINHOLE (fx used), SIMPLE_
// RADIAL or RADIAL cameras and the principal point at the image centre:
// camera i is the image named image_names[i] (unregistered when missing
// from the model). Used to write 1DSfM-style test scenes.
BundlerFile ReconstructionToBundler(
    const Reconstruction& reconstruction,
    const std::vector<std::string>& image_names);

// 1DSfM's list.txt: one image path per line, optionally followed by other
// fields (e.g. "images/a.jpg 0 1234.5"); returns the paths.
std::vector<std::string> ReadBundlerImageList(const std::string& path);

}  // namespace colmap_gcn
