#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "synthetic/camera.h"
#include "synthetic/random.h"
#include "synthetic/scene.h"

namespace colmap_gcn {

// Screen-space binning of a scene's triangles for one camera: every triangle
// is listed in each tile (tile_size x tile_size pixels) that its projection
// (after clipping against the near plane) may touch. Any ray from the camera
// centre through a point of a tile can only hit triangles listed there, so
// casting against the tile's list is exact.
class TriangleBins {
 public:
  TriangleBins(const Scene& scene,
               const PinholeCamera& camera,
               int tile_size = 16);

  // Triangles possibly covering image coordinate (x, y) (inside the image).
  const std::vector<int>& TrianglesAt(double x, double y) const;

  static constexpr double kNearPlane = 1e-3;

 private:
  int tile_size_;
  int tiles_x_;
  int tiles_y_;
  std::vector<std::vector<int>> bins_;
};

struct RayHit {
  int triangle = -1;
  double t = 0.0;
  double b1 = 0.0;
  double b2 = 0.0;
};

// Nearest hit among `candidates` of origin + t * dir, t in (t_min, t_max).
RayHit CastRay(const Scene& scene,
               const std::vector<int>& candidates,
               const Eigen::Vector3d& origin,
               const Eigen::Vector3d& dir,
               double t_min,
               double t_max);

// Per-image photometric variation applied after shading.
struct PhotometricParams {
  double gain = 1.0;         // exposure
  double bias = 0.0;         // black level, grey levels
  double blur_sigma = 0.0;   // Gaussian defocus, pixels
  double noise_sigma = 0.0;  // additive Gaussian noise, grey levels
  uint64_t noise_seed = 0;

  // Mild random variation: gain 0.8-1.2, bias +-8, blur 0.3-0.9 px,
  // noise 1-3 grey levels.
  static PhotometricParams Random(SyntheticRandom* rng);
};

// Renders the scene (8-bit BGR): one ray per pixel through the pixel centre,
// nearest hit, trilinear mipmapped texture lookup, Lambertian shading, sky
// where nothing is hit, then the photometric variation.
cv::Mat RenderImage(const Scene& scene,
                    const PinholeCamera& camera,
                    const PhotometricParams& photometric);

}  // namespace colmap_gcn
