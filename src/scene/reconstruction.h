#pragma once

#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "util/types.h"

namespace colmap_gcn {

struct ModelCamera {
  camera_t camera_id = kInvalidCameraId;
  int model_id = -1;  // see camera_models.h
  uint64_t width = 0;
  uint64_t height = 0;
  std::vector<double> params;
};

struct ModelImage {
  image_t image_id = kInvalidImageId;
  // World-to-camera rotation as quaternion (w, x, y, z) and translation.
  Eigen::Vector4d qvec = Eigen::Vector4d(1, 0, 0, 0);
  Eigen::Vector3d tvec = Eigen::Vector3d::Zero();
  camera_t camera_id = kInvalidCameraId;
  std::string name;
  std::vector<Eigen::Vector2d> points2D;
  std::vector<point3D_t> point3D_ids;  // kInvalidPoint3DId if none

  Eigen::Matrix3d RotationMatrix() const;    // world-to-camera
  Eigen::Vector3d ProjectionCenter() const;  // -R^T t
  size_t NumPoints3D() const;  // observations with a valid point3D id
};

struct TrackElement {
  image_t image_id = kInvalidImageId;
  point2D_t point2D_idx = kInvalidPoint2DIdx;
};

struct ModelPoint3D {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  Eigen::Matrix<uint8_t, 3, 1> color = Eigen::Matrix<uint8_t, 3, 1>::Zero();
  double error = -1.0;
  std::vector<TrackElement> track;
};

// A COLMAP sparse model (cameras, images, points3D) with readers and writers
// for both the binary (.bin) and text (.txt) formats of COLMAP 3.x. Readers
// throw Error with a one-line message naming the file on any malformed,
// truncated or missing input.
class Reconstruction {
 public:
  std::map<camera_t, ModelCamera> cameras;
  std::map<image_t, ModelImage> images;
  std::map<point3D_t, ModelPoint3D> points3D;

  // Reads from a folder holding either cameras.bin/images.bin/points3D.bin or
  // the .txt files (binary preferred when all three .bin files exist). In the
  // text format a missing points3D.txt is read as an empty point set (ground
  // truth folders carry only poses); cameras.txt and images.txt are required.
  // The writer creates the folder if needed and writes full double
  // precision.
  void Read(const std::string& path);
  void ReadText(const std::string& path);
  void ReadBinary(const std::string& path);
  void WriteText(const std::string& path) const;

  // Image id by name, or kInvalidImageId.
  image_t FindImageWithName(const std::string& name) const;
};

}  // namespace colmap_gcn
