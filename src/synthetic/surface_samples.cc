#include "synthetic/surface_samples.h"

#include <algorithm>
#include <cmath>

#include "synthetic/random.h"

namespace colmap_gcn {

std::vector<SurfaceSample> SampleSurfaces(const Scene& scene,
                                          int num_samples,
                                          uint64_t seed) {
  std::vector<double> cumulative_area;
  cumulative_area.reserve(scene.triangles.size());
  double total_area = 0.0;
  for (const SceneTriangle& tri : scene.triangles) {
    total_area += tri.area;
    cumulative_area.push_back(total_area);
  }
  std::vector<SurfaceSample> samples;
  if (total_area <= 0.0) {
    return samples;
  }
  SyntheticRandom rng(SyntheticRandom::Mix(seed, 0x5a3b1e));
  samples.reserve(num_samples);
  for (int i = 0; i < num_samples; ++i) {
    const double target = rng.Uniform() * total_area;
    const int tri_idx = static_cast<int>(std::min<size_t>(
        std::upper_bound(
            cumulative_area.begin(), cumulative_area.end(), target) -
            cumulative_area.begin(),
        scene.triangles.size() - 1));
    // Uniform point in a triangle: fold the unit square.
    double b1 = rng.Uniform();
    double b2 = rng.Uniform();
    if (b1 + b2 > 1.0) {
      b1 = 1.0 - b1;
      b2 = 1.0 - b2;
    }
    const SceneTriangle& tri = scene.triangles[tri_idx];
    SurfaceSample sample;
    sample.xyz = tri.Point(b1, b2);
    sample.triangle = tri_idx;
    if (!scene.textures.empty()) {
      sample.color = scene.Shade(tri_idx, b1, b2, 0.0, -tri.normal);
    }
    samples.push_back(sample);
  }
  return samples;
}

std::vector<SampleObservation> ComputeVisibleSamples(
    const Scene& scene,
    const TriangleBins& bins,
    const PinholeCamera& camera,
    const std::vector<SurfaceSample>& samples,
    double min_cos) {
  std::vector<SampleObservation> visible;
  const Eigen::Vector3d center = camera.Center();
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
    const SurfaceSample& sample = samples[i];
    const SceneTriangle& tri = scene.triangles[sample.triangle];
    const Eigen::Vector3d to_camera = center - sample.xyz;
    const double distance = to_camera.norm();
    if (distance <= TriangleBins::kNearPlane ||
        tri.normal.dot(to_camera) <= min_cos * distance) {
      continue;
    }
    Eigen::Vector2d xy;
    if (!camera.Project(sample.xyz, &xy, TriangleBins::kNearPlane) ||
        !camera.IsInImage(xy)) {
      continue;
    }
    // Occlusion: any other triangle hit strictly before the sample. The ray
    // has unit length to the sample, so t is a fraction of the distance.
    const Eigen::Vector3d dir = -to_camera;
    bool occluded = false;
    double t, b1, b2;
    const double t_max = 1.0 - 1e-7;
    for (const int idx : bins.TrianglesAt(xy.x(), xy.y())) {
      if (idx != sample.triangle &&
          scene.triangles[idx].Intersect(
              center, dir, 1e-9, t_max, &t, &b1, &b2)) {
        occluded = true;
        break;
      }
    }
    if (!occluded) {
      SampleObservation observation;
      observation.sample_idx = i;
      observation.xy = xy;
      visible.push_back(observation);
    }
  }
  return visible;
}

}  // namespace colmap_gcn
