#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "synthetic/camera.h"
#include "synthetic/renderer.h"
#include "synthetic/scene.h"

namespace colmap_gcn {

// A point on the scene surface: the unit of ground-truth overlap.
struct SurfaceSample {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  int triangle = -1;
  Eigen::Vector3f color = Eigen::Vector3f::Zero();  // shaded, BGR
};

// num_samples points uniformly distributed over the scene's surface area
// (triangle chosen proportionally to its area, then a uniform point in it),
// deterministic for the seed.
std::vector<SurfaceSample> SampleSurfaces(const Scene& scene,
                                          int num_samples,
                                          uint64_t seed);

struct SampleObservation {
  int sample_idx = -1;
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  // COLMAP image coordinates
};

// Samples the camera sees: in front of it, projecting inside the image,
// front side facing the camera (cosine between normal and viewing ray above
// min_cos) and not occluded (no triangle hit by the ray from the camera
// centre before the sample). Sorted by sample index.
std::vector<SampleObservation> ComputeVisibleSamples(
    const Scene& scene,
    const TriangleBins& bins,
    const PinholeCamera& camera,
    const std::vector<SurfaceSample>& samples,
    double min_cos);

}  // namespace colmap_gcn
