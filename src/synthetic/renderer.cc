#include "synthetic/renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

namespace colmap_gcn {

TriangleBins::TriangleBins(const Scene& scene,
                           const PinholeCamera& camera,
                           int tile_size)
    : tile_size_(tile_size),
      tiles_x_((camera.width + tile_size - 1) / tile_size),
      tiles_y_((camera.height + tile_size - 1) / tile_size),
      bins_(static_cast<size_t>(tiles_x_) * tiles_y_) {
  const double kHuge = 1e7;
  for (int idx = 0; idx < static_cast<int>(scene.triangles.size()); ++idx) {
    const SceneTriangle& tri = scene.triangles[idx];
    const Eigen::Vector3d p[3] = {camera.ToCamera(tri.v0),
                                  camera.ToCamera(tri.v0 + tri.e1),
                                  camera.ToCamera(tri.v0 + tri.e2)};
    double min_x = std::numeric_limits<double>::infinity();
    double min_y = min_x;
    double max_x = -min_x;
    double max_y = -min_x;
    int num_points = 0;
    auto add = [&](const Eigen::Vector3d& q) {
      const double x =
          std::clamp(camera.fx * q.x() / q.z() + camera.cx, -kHuge, kHuge);
      const double y =
          std::clamp(camera.fy * q.y() / q.z() + camera.cy, -kHuge, kHuge);
      min_x = std::min(min_x, x);
      max_x = std::max(max_x, x);
      min_y = std::min(min_y, y);
      max_y = std::max(max_y, y);
      ++num_points;
    };
    // Clip against the near plane: the projection of the clipped triangle
    // is the convex hull of its front vertices and the edge crossings.
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& a = p[k];
      const Eigen::Vector3d& b = p[(k + 1) % 3];
      const bool a_front = a.z() > kNearPlane;
      const bool b_front = b.z() > kNearPlane;
      if (a_front) {
        add(a);
      }
      if (a_front != b_front) {
        const double s = (kNearPlane - a.z()) / (b.z() - a.z());
        Eigen::Vector3d q = a + s * (b - a);
        q.z() = kNearPlane;
        add(q);
      }
    }
    if (num_points == 0) {
      continue;  // entirely behind the camera
    }
    // One pixel of margin against rounding.
    const int tx0 =
        static_cast<int>(std::floor(std::max(0.0, min_x - 1.0) / tile_size_));
    const int ty0 =
        static_cast<int>(std::floor(std::max(0.0, min_y - 1.0) / tile_size_));
    const int tx1 = static_cast<int>(
        std::floor(std::min(camera.width - 1e-9, max_x + 1.0) / tile_size_));
    const int ty1 = static_cast<int>(
        std::floor(std::min(camera.height - 1e-9, max_y + 1.0) / tile_size_));
    for (int ty = ty0; ty <= ty1 && ty < tiles_y_; ++ty) {
      for (int tx = tx0; tx <= tx1 && tx < tiles_x_; ++tx) {
        bins_[static_cast<size_t>(ty) * tiles_x_ + tx].push_back(idx);
      }
    }
  }
}

const std::vector<int>& TriangleBins::TrianglesAt(double x, double y) const {
  const int tx = std::clamp(static_cast<int>(x) / tile_size_, 0, tiles_x_ - 1);
  const int ty = std::clamp(static_cast<int>(y) / tile_size_, 0, tiles_y_ - 1);
  return bins_[static_cast<size_t>(ty) * tiles_x_ + tx];
}

RayHit CastRay(const Scene& scene,
               const std::vector<int>& candidates,
               const Eigen::Vector3d& origin,
               const Eigen::Vector3d& dir,
               double t_min,
               double t_max) {
  RayHit hit;
  double t, b1, b2;
  for (const int idx : candidates) {
    if (scene.triangles[idx].Intersect(
            origin, dir, t_min, t_max, &t, &b1, &b2)) {
      t_max = t;
      hit.triangle = idx;
      hit.t = t;
      hit.b1 = b1;
      hit.b2 = b2;
    }
  }
  return hit;
}

PhotometricParams PhotometricParams::Random(SyntheticRandom* rng) {
  PhotometricParams params;
  params.gain = rng->Uniform(0.8, 1.2);
  params.bias = rng->Uniform(-8.0, 8.0);
  params.blur_sigma = rng->Uniform(0.3, 0.9);
  params.noise_sigma = rng->Uniform(1.0, 3.0);
  params.noise_seed = rng->Next();
  return params;
}

cv::Mat RenderImage(const Scene& scene,
                    const PinholeCamera& camera,
                    const PhotometricParams& photometric) {
  const TriangleBins bins(scene, camera);
  const Eigen::Vector3d origin = camera.Center();
  const Eigen::Matrix3d Rt = camera.R.transpose();
  const double focal = 0.5 * (camera.fx + camera.fy);
  cv::Mat radiance(camera.height, camera.width, CV_32FC3);
  for (int y = 0; y < camera.height; ++y) {
    cv::Vec3f* row = radiance.ptr<cv::Vec3f>(y);
    for (int x = 0; x < camera.width; ++x) {
      const double px = x + 0.5;
      const double py = y + 0.5;
      // Unnormalised direction with unit depth: t is the depth.
      const Eigen::Vector3d dir_cam(
          (px - camera.cx) / camera.fx, (py - camera.cy) / camera.fy, 1.0);
      const Eigen::Vector3d dir = Rt * dir_cam;
      const RayHit hit = CastRay(scene,
                                 bins.TrianglesAt(px, py),
                                 origin,
                                 dir,
                                 TriangleBins::kNearPlane,
                                 std::numeric_limits<double>::max());
      Eigen::Vector3f color;
      if (hit.triangle < 0) {
        color = scene.SkyColor(dir);
      } else {
        const SceneTriangle& tri = scene.triangles[hit.triangle];
        const double dir_norm = dir.norm();
        const double distance = hit.t * dir_norm;
        // Pixel footprint on the surface in texels; the slant widens it in
        // one direction, isotropic mipmapping takes the geometric mean.
        const double cos_angle =
            std::max(0.05, std::abs(tri.normal.dot(dir)) / dir_norm);
        const double footprint =
            distance * tri.texels_per_unit / (focal * std::sqrt(cos_angle));
        const double lod = std::log2(std::max(1.0, footprint));
        color = scene.Shade(hit.triangle, hit.b1, hit.b2, lod, dir);
      }
      row[x] = cv::Vec3f(color(0), color(1), color(2));
    }
  }

  radiance = radiance * photometric.gain + cv::Scalar::all(photometric.bias);
  if (photometric.blur_sigma > 0.0) {
    cv::GaussianBlur(radiance,
                     radiance,
                     cv::Size(0, 0),
                     photometric.blur_sigma,
                     photometric.blur_sigma,
                     cv::BORDER_REFLECT);
  }
  cv::Mat image(camera.height, camera.width, CV_8UC3);
  SyntheticRandom rng(photometric.noise_seed);
  const float noise_sigma = static_cast<float>(photometric.noise_sigma);
  for (int y = 0; y < camera.height; ++y) {
    const float* in = radiance.ptr<float>(y);
    uint8_t* out = image.ptr<uint8_t>(y);
    for (int i = 0; i < 3 * camera.width; ++i) {
      float value = in[i];
      if (photometric.noise_sigma > 0.0) {
        // Approximately normal: the sum of four uniform 16-bit draws taken
        // from one 64-bit random number (mean 2, variance 1/3), rescaled.
        const uint64_t r = rng.Next();
        const float sum =
            static_cast<float>((r & 0xFFFF) + ((r >> 16) & 0xFFFF) +
                               ((r >> 32) & 0xFFFF) + (r >> 48)) *
            (1.0f / 65536.0f);
        value += noise_sigma * (sum - 2.0f) * 1.7320508f;
      }
      out[i] = static_cast<uint8_t>(std::clamp(value, 0.0f, 255.0f) + 0.5f);
    }
  }
  return image;
}

}  // namespace colmap_gcn
