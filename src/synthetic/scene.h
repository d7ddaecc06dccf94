#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "synthetic/texture.h"

namespace colmap_gcn {

// A textured triangle. The front side is the one its normal (e1 x e2) points
// to; rays hit both sides (back faces still occlude), but only the front side
// counts as visible surface in the ground truth.
struct SceneTriangle {
  Eigen::Vector3d v0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d e1 = Eigen::Vector3d::Zero();  // v1 - v0
  Eigen::Vector3d e2 = Eigen::Vector3d::Zero();  // v2 - v0
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  // Texture coordinates of v0 and their differences at v1 and v2.
  Eigen::Vector2d uv0 = Eigen::Vector2d::Zero();
  Eigen::Vector2d duv1 = Eigen::Vector2d::Zero();
  Eigen::Vector2d duv2 = Eigen::Vector2d::Zero();
  int texture_id = -1;
  double area = 0.0;
  // Texels (of mipmap level 0) per world unit, for mipmap selection.
  double texels_per_unit = 1.0;

  Eigen::Vector3d Point(double b1, double b2) const {
    return v0 + b1 * e1 + b2 * e2;
  }
  Eigen::Vector2d Uv(double b1, double b2) const {
    return uv0 + b1 * duv1 + b2 * duv2;
  }

  // Moller-Trumbore intersection of origin + t * dir for t in (t_min, t_max);
  // dir need not be normalised. On a hit sets *t and barycentrics b1, b2.
  inline bool Intersect(const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& dir,
                        double t_min,
                        double t_max,
                        double* t,
                        double* b1,
                        double* b2) const {
    const Eigen::Vector3d pvec = dir.cross(e2);
    const double det = e1.dot(pvec);
    if (det > -1e-14 && det < 1e-14) {
      return false;
    }
    const double inv_det = 1.0 / det;
    const Eigen::Vector3d tvec = origin - v0;
    const double u = tvec.dot(pvec) * inv_det;
    if (u < 0.0 || u > 1.0) {
      return false;
    }
    const Eigen::Vector3d qvec = tvec.cross(e1);
    const double v = dir.dot(qvec) * inv_det;
    if (v < 0.0 || u + v > 1.0) {
      return false;
    }
    const double hit_t = e2.dot(qvec) * inv_det;
    if (hit_t <= t_min || hit_t >= t_max) {
      return false;
    }
    *t = hit_t;
    *b1 = u;
    *b2 = v;
    return true;
  }
};

// How a texture is made; textures are materialised in parallel after the
// geometry is built (GenerateTextures), each from its own seed.
struct TextureSpec {
  enum class Kind { kRandom, kWindowTile, kSmooth, kUser };
  Kind kind = Kind::kRandom;
  uint64_t seed = 0;
  int width = 512;
  int height = 512;
  int user_index = -1;  // for kUser: index into the user texture images
};

// Triangles, textures and lighting. Lambertian shading with one directional
// light, fixed in the world, so appearance does not depend on the viewpoint.
class Scene {
 public:
  std::vector<SceneTriangle> triangles;
  std::vector<TextureSpec> texture_specs;
  std::vector<Texture> textures;  // filled by GenerateTextures

  Eigen::Vector3d light_direction = Eigen::Vector3d(0.4, 0.3, 0.85);
  float ambient = 0.55f;
  float diffuse = 0.5f;
  // Featureless sky gradient (BGR) for rays that hit nothing.
  Eigen::Vector3f sky_zenith = Eigen::Vector3f(215.f, 170.f, 120.f);
  Eigen::Vector3f sky_horizon = Eigen::Vector3f(240.f, 230.f, 220.f);

  int AddTexture(const TextureSpec& spec);

  // Adds triangle (a, b, c) with texture coordinates; front side is the one
  // from which a, b, c appear counter-clockwise.
  void AddTriangle(const Eigen::Vector3d& a,
                   const Eigen::Vector3d& b,
                   const Eigen::Vector3d& c,
                   const Eigen::Vector2d& uv_a,
                   const Eigen::Vector2d& uv_b,
                   const Eigen::Vector2d& uv_c,
                   int texture_id);

  // Planar quad given bottom-left, bottom-right, top-right, top-left as seen
  // from its front. The texture appears upright, repeated repeat_u times
  // horizontally and repeat_v times vertically, starting at uv_offset.
  void AddQuad(const Eigen::Vector3d& p0,
               const Eigen::Vector3d& p1,
               const Eigen::Vector3d& p2,
               const Eigen::Vector3d& p3,
               int texture_id,
               double repeat_u = 1.0,
               double repeat_v = 1.0,
               const Eigen::Vector2d& uv_offset = Eigen::Vector2d::Zero());

  // Triangle fan (center, rim[k], rim[k+1]) for k over the closed rim; the
  // front side is the one from which the rim runs counter-clockwise. Texture
  // coordinates are local to each triangle (x axis along rim[k] - center), so
  // congruent triangles get identical textures; one repeat per
  // texture_world_size units.
  void AddFan(const Eigen::Vector3d& center,
              const std::vector<Eigen::Vector3d>& rim,
              int texture_id,
              double texture_world_size);

  // Vertical prism over a convex footprint (x, y vertices counter-clockwise
  // seen from above) between heights z0 and z1, outward-facing sides. Side k
  // (from footprint[k] to footprint[k+1]) uses side_textures[k % size] with
  // the texture repeated once per `texture_world_size` units (<= 0: once per
  // side). top_texture < 0: no top face (top faces are triangle fans).
  void AddPrism(const std::vector<Eigen::Vector2d>& footprint,
                double z0,
                double z1,
                const std::vector<int>& side_textures,
                int top_texture,
                double texture_world_size);

  // Axis-aligned box (rotated by yaw about z) standing on z = z0.
  void AddBox(const Eigen::Vector2d& center,
              const Eigen::Vector2d& size,
              double yaw,
              double z0,
              double height,
              const std::vector<int>& side_textures,
              int top_texture,
              double texture_world_size);

  // Materialises texture_specs into textures (in parallel, deterministic).
  void GenerateTextures(const std::vector<cv::Mat>& user_images,
                        int num_threads);

  // Recomputes the texel densities once textures exist.
  void UpdateTexelDensities();

  // Shaded surface colour (BGR) of triangle `tri` at barycentrics (b1, b2)
  // seen along `ray_dir` at mipmap level `lod`.
  Eigen::Vector3f Shade(int tri,
                        double b1,
                        double b2,
                        double lod,
                        const Eigen::Vector3d& ray_dir) const;

  Eigen::Vector3f SkyColor(const Eigen::Vector3d& ray_dir) const;
};

// Regular polygon footprint with n vertices on a circle (counter-clockwise),
// the first at angle `phase`.
std::vector<Eigen::Vector2d> RegularPolygon(
    int n,
    double radius,
    double phase,
    const Eigen::Vector2d& center = Eigen::Vector2d::Zero());

}  // namespace colmap_gcn
