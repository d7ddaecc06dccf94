#include "synthetic/scene.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"
#include "util/threading.h"

namespace colmap_gcn {

int Scene::AddTexture(const TextureSpec& spec) {
  texture_specs.push_back(spec);
  return static_cast<int>(texture_specs.size()) - 1;
}

void Scene::AddTriangle(const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c,
                        const Eigen::Vector2d& uv_a,
                        const Eigen::Vector2d& uv_b,
                        const Eigen::Vector2d& uv_c,
                        int texture_id) {
  SceneTriangle tri;
  tri.v0 = a;
  tri.e1 = b - a;
  tri.e2 = c - a;
  const Eigen::Vector3d cross = tri.e1.cross(tri.e2);
  tri.area = 0.5 * cross.norm();
  if (tri.area <= 1e-12) {
    return;  // degenerate
  }
  tri.normal = cross.normalized();
  tri.uv0 = uv_a;
  tri.duv1 = uv_b - uv_a;
  tri.duv2 = uv_c - uv_a;
  tri.texture_id = texture_id;
  triangles.push_back(tri);
}

void Scene::AddQuad(const Eigen::Vector3d& p0,
                    const Eigen::Vector3d& p1,
                    const Eigen::Vector3d& p2,
                    const Eigen::Vector3d& p3,
                    int texture_id,
                    double repeat_u,
                    double repeat_v,
                    const Eigen::Vector2d& uv_offset) {
  const Eigen::Vector2d uv0 = uv_offset + Eigen::Vector2d(0.0, repeat_v);
  const Eigen::Vector2d uv1 = uv_offset + Eigen::Vector2d(repeat_u, repeat_v);
  const Eigen::Vector2d uv2 = uv_offset + Eigen::Vector2d(repeat_u, 0.0);
  const Eigen::Vector2d uv3 = uv_offset;
  AddTriangle(p0, p1, p2, uv0, uv1, uv2, texture_id);
  AddTriangle(p0, p2, p3, uv0, uv2, uv3, texture_id);
}

void Scene::AddFan(const Eigen::Vector3d& center,
                   const std::vector<Eigen::Vector3d>& rim,
                   int texture_id,
                   double texture_world_size) {
  const int n = static_cast<int>(rim.size());
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d& a = rim[k];
    const Eigen::Vector3d& b = rim[(k + 1) % n];
    const Eigen::Vector3d normal = (a - center).cross(b - center);
    if (normal.norm() < 1e-12) continue;
    const Eigen::Vector3d x_axis = (a - center).normalized();
    const Eigen::Vector3d y_axis = normal.normalized().cross(x_axis);
    auto uv = [&](const Eigen::Vector3d& p) {
      // Texture v runs downwards: flip y so the texture is not mirrored.
      const Eigen::Vector3d d = p - center;
      const double u_coord = d.dot(x_axis) / texture_world_size;
      const double v_coord = -d.dot(y_axis) / texture_world_size;
      return Eigen::Vector2d(u_coord, v_coord);
    };
    AddTriangle(center, a, b, uv(center), uv(a), uv(b), texture_id);
  }
}

void Scene::AddPrism(const std::vector<Eigen::Vector2d>& footprint,
                     double z0,
                     double z1,
                     const std::vector<int>& side_textures,
                     int top_texture,
                     double texture_world_size) {
  const int n = static_cast<int>(footprint.size());
  const double height = z1 - z0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d& a = footprint[k];
    const Eigen::Vector2d& b = footprint[(k + 1) % n];
    const double width = (b - a).norm();
    const double repeat_u =
        texture_world_size > 0 ? width / texture_world_size : 1.0;
    const double repeat_v =
        texture_world_size > 0 ? height / texture_world_size : 1.0;
    AddQuad(Eigen::Vector3d(a.x(), a.y(), z0),
            Eigen::Vector3d(b.x(), b.y(), z0),
            Eigen::Vector3d(b.x(), b.y(), z1),
            Eigen::Vector3d(a.x(), a.y(), z1),
            side_textures[k % side_textures.size()],
            repeat_u,
            repeat_v);
  }
  if (top_texture >= 0) {
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    std::vector<Eigen::Vector3d> rim;
    for (const auto& p : footprint) {
      centroid += p;
      rim.emplace_back(p.x(), p.y(), z1);
    }
    centroid /= n;
    AddFan(Eigen::Vector3d(centroid.x(), centroid.y(), z1),
           rim,
           top_texture,
           texture_world_size > 0 ? texture_world_size : 1.0);
  }
}

void Scene::AddBox(const Eigen::Vector2d& center,
                   const Eigen::Vector2d& size,
                   double yaw,
                   double z0,
                   double height,
                   const std::vector<int>& side_textures,
                   int top_texture,
                   double texture_world_size) {
  const Eigen::Rotation2Dd rotation(yaw);
  const Eigen::Vector2d h = 0.5 * size;
  std::vector<Eigen::Vector2d> footprint = {
      center + rotation * Eigen::Vector2d(-h.x(), -h.y()),
      center + rotation * Eigen::Vector2d(h.x(), -h.y()),
      center + rotation * Eigen::Vector2d(h.x(), h.y()),
      center + rotation * Eigen::Vector2d(-h.x(), h.y())};
  AddPrism(footprint,
           z0,
           z0 + height,
           side_textures,
           top_texture,
           texture_world_size);
}

void Scene::GenerateTextures(const std::vector<cv::Mat>& user_images,
                             int num_threads) {
  textures.assign(texture_specs.size(), Texture());
  ParallelFor(
      0, static_cast<int>(texture_specs.size()), num_threads, [&](int i) {
        const TextureSpec& spec = texture_specs[i];
        cv::Mat image;
        switch (spec.kind) {
          case TextureSpec::Kind::kRandom:
            image = GenerateRandomTexture(spec.seed, spec.width, spec.height);
            break;
          case TextureSpec::Kind::kWindowTile:
            image =
                GenerateWindowTileTexture(spec.seed, spec.width, spec.height);
            break;
          case TextureSpec::Kind::kSmooth:
            image = GenerateSmoothTexture(spec.seed, spec.width, spec.height);
            break;
          case TextureSpec::Kind::kUser:
            THROW_CHECK(spec.user_index >= 0 &&
                        spec.user_index < static_cast<int>(user_images.size()));
            image = user_images[spec.user_index];
            break;
        }
        textures[i] = Texture(image);
      });
  UpdateTexelDensities();
}

void Scene::UpdateTexelDensities() {
  for (SceneTriangle& tri : triangles) {
    if (tri.texture_id < 0 ||
        tri.texture_id >= static_cast<int>(textures.size())) {
      continue;
    }
    const Texture& texture = textures[tri.texture_id];
    const double uv_area =
        0.5 *
        std::abs(tri.duv1.x() * tri.duv2.y() - tri.duv1.y() * tri.duv2.x()) *
        texture.Width() * texture.Height();
    tri.texels_per_unit = std::sqrt(uv_area / tri.area);
  }
}

Eigen::Vector3f Scene::Shade(int tri_idx,
                             double b1,
                             double b2,
                             double lod,
                             const Eigen::Vector3d& ray_dir) const {
  const SceneTriangle& tri = triangles[tri_idx];
  const Eigen::Vector2d uv = tri.Uv(b1, b2);
  const Eigen::Vector3f albedo =
      textures[tri.texture_id].Sample(uv.x(), uv.y(), lod);
  Eigen::Vector3d n = tri.normal;
  if (n.dot(ray_dir) > 0.0) {
    n = -n;
  }
  const float lambert =
      static_cast<float>(std::max(0.0, n.dot(light_direction)));
  return albedo * (ambient + diffuse * lambert);
}

Eigen::Vector3f Scene::SkyColor(const Eigen::Vector3d& ray_dir) const {
  const float elevation = static_cast<float>(
      std::clamp(ray_dir.z() / std::max(ray_dir.norm(), 1e-12), 0.0, 1.0));
  return (1.0f - elevation) * sky_horizon + elevation * sky_zenith;
}

std::vector<Eigen::Vector2d> RegularPolygon(int n,
                                            double radius,
                                            double phase,
                                            const Eigen::Vector2d& center) {
  std::vector<Eigen::Vector2d> polygon;
  for (int k = 0; k < n; ++k) {
    const double angle = phase + 2.0 * M_PI * k / n;
    polygon.push_back(
        center + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
  return polygon;
}

}  // namespace colmap_gcn
