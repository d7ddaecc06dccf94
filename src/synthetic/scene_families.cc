#include "synthetic/scene_families.h"

#include <algorithm>
#include <cmath>

#include "synthetic/random.h"

namespace colmap_gcn {
namespace {

// Hands out texture specs with fresh seeds (or user images, cycled).
class TextureFactory {
 public:
  TextureFactory(Scene* scene, const WorldParams& params, uint64_t stream)
      : scene_(scene),
        params_(params),
        rng_(SyntheticRandom::Mix(params.seed, stream)) {}

  int Random(int width, int height) {
    TextureSpec spec;
    spec.seed = rng_.Next();
    spec.width = Scaled(width);
    spec.height = Scaled(height);
    if (params_.num_user_textures > 0) {
      spec.kind = TextureSpec::Kind::kUser;
      spec.user_index = next_user_++ % params_.num_user_textures;
    }
    return scene_->AddTexture(spec);
  }

  int WindowTile(int size) {
    TextureSpec spec;
    spec.kind = TextureSpec::Kind::kWindowTile;
    spec.seed = rng_.Next();
    spec.width = Scaled(size);
    spec.height = Scaled(size);
    return scene_->AddTexture(spec);
  }

  int Smooth(int size) {
    TextureSpec spec;
    spec.kind = TextureSpec::Kind::kSmooth;
    spec.seed = rng_.Next();
    spec.width = Scaled(size);
    spec.height = Scaled(size);
    return scene_->AddTexture(spec);
  }

 private:
  int Scaled(int size) const {
    return std::max(32,
                    static_cast<int>(std::lround(
                        size * std::clamp(params_.texture_scale, 0.125, 4.0))));
  }

  Scene* scene_;
  const WorldParams& params_;
  SyntheticRandom rng_;
  int next_user_ = 0;
};

// Cameras on an ellipse (semi-axes rx, ry) around `target`, evenly spread in
// angle with jitter, heights in [z_min, z_max], looking at the target with a
// little jitter and roll.
std::vector<PinholeCamera> OrbitCameras(const WorldParams& params,
                                        SyntheticRandom* rng,
                                        const Eigen::Vector3d& target,
                                        double rx,
                                        double ry,
                                        double z_min,
                                        double z_max,
                                        double target_jitter) {
  std::vector<PinholeCamera> cameras;
  const int n = params.num_images;
  const double phase = rng->Uniform(0.0, 2.0 * M_PI);
  const double step = 2.0 * M_PI / std::max(1, n);
  for (int i = 0; i < n; ++i) {
    const double angle = phase + i * step + rng->Uniform(-0.25, 0.25) * step;
    const double radius_scale = rng->Uniform(0.93, 1.07);
    const Eigen::Vector3d center(radius_scale * rx * std::cos(angle),
                                 radius_scale * ry * std::sin(angle),
                                 rng->Uniform(z_min, z_max));
    const Eigen::Vector3d look_at =
        target + Eigen::Vector3d(rng->Uniform(-1, 1),
                                 rng->Uniform(-1, 1),
                                 rng->Uniform(-0.5, 0.5)) *
                     target_jitter;
    cameras.push_back(LookAtCamera(center,
                                   look_at,
                                   rng->Uniform(-0.05, 0.05),
                                   params.width,
                                   params.height,
                                   params.focal_length));
  }
  return cameras;
}

// Square ground of half-size g with one unique texture.
void AddGround(Scene* scene, TextureFactory* textures, double g) {
  const int tex = textures->Random(2048, 2048);
  scene->AddQuad(Eigen::Vector3d(-g, -g, 0),
                 Eigen::Vector3d(g, -g, 0),
                 Eigen::Vector3d(g, g, 0),
                 Eigen::Vector3d(-g, g, 0),
                 tex);
}

// Inward-facing background walls around the square ground, segments_per_side
// segments per side, each with its own texture.
void AddBackgroundRing(Scene* scene,
                       TextureFactory* textures,
                       double g,
                       double height,
                       int segments_per_side) {
  std::vector<Eigen::Vector2d> corners = {
      {-g, -g}, {-g, g}, {g, g}, {g, -g}};  // clockwise: walls face inwards
  std::vector<Eigen::Vector2d> footprint;
  std::vector<int> side_textures;
  for (int k = 0; k < 4; ++k) {
    for (int s = 0; s < segments_per_side; ++s) {
      const double a = static_cast<double>(s) / segments_per_side;
      footprint.push_back((1 - a) * corners[k] + a * corners[(k + 1) % 4]);
      side_textures.push_back(textures->Random(1024, 512));
    }
  }
  scene->AddPrism(footprint, 0.0, height, side_textures, -1, 0.0);
}

}  // namespace

SyntheticWorld BuildOrdinaryWorld(const WorldParams& params) {
  SyntheticWorld world;
  Scene& scene = world.scene;
  TextureFactory textures(&scene, params, 1);
  SyntheticRandom rng(SyntheticRandom::Mix(params.seed, 2));
  const double orbit_radius = 12.0;
  const double g = orbit_radius + 6.0;
  AddGround(&scene, &textures, g);
  AddBackgroundRing(&scene, &textures, g, 6.0, 3);

  auto unique_sides = [&](int n, int size) {
    std::vector<int> ids;
    for (int k = 0; k < n; ++k) ids.push_back(textures.Random(size, size));
    return ids;
  };
  // Main block.
  const double main_w = rng.Uniform(5.0, 7.0);
  const double main_d = rng.Uniform(3.5, 5.0);
  const double main_h = rng.Uniform(3.5, 5.0);
  const double yaw = rng.Uniform(0.0, M_PI);
  scene.AddBox(Eigen::Vector2d::Zero(),
               Eigen::Vector2d(main_w, main_d),
               yaw,
               0.0,
               main_h,
               unique_sides(4, 1024),
               textures.Random(512, 512),
               0.0);
  const Eigen::Rotation2Dd rotation(yaw);
  // Annex against one long side.
  const double annex_w = rng.Uniform(2.5, 3.5);
  scene.AddBox(rotation * Eigen::Vector2d(rng.Uniform(-1.5, 1.5),
                                          0.5 * main_d + 0.5 * annex_w - 0.2),
               Eigen::Vector2d(annex_w, annex_w),
               yaw,
               0.0,
               rng.Uniform(2.0, 3.0),
               unique_sides(4, 512),
               textures.Random(512, 512),
               0.0);
  // Tower at a corner.
  scene.AddBox(rotation * Eigen::Vector2d(0.5 * main_w, -0.5 * main_d),
               Eigen::Vector2d(1.4, 1.4),
               yaw + 0.3,
               0.0,
               rng.Uniform(6.0, 8.0),
               unique_sides(4, 512),
               textures.Random(256, 256),
               0.0);
  // Crates scattered around.
  const int num_crates = rng.UniformInt(4, 6);
  for (int c = 0; c < num_crates; ++c) {
    const double angle = 2.0 * M_PI * (c + rng.Uniform(0.0, 0.6)) / num_crates;
    const double radius = rng.Uniform(5.0, 7.5);
    const double size = rng.Uniform(0.6, 1.3);
    scene.AddBox(radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)),
                 Eigen::Vector2d(size, size * rng.Uniform(0.7, 1.3)),
                 rng.Uniform(0.0, M_PI),
                 0.0,
                 size * rng.Uniform(0.7, 1.5),
                 unique_sides(4, 256),
                 textures.Random(256, 256),
                 0.0);
  }

  world.target = Eigen::Vector3d(0, 0, 2.0);
  world.cameras = OrbitCameras(
      params, &rng, world.target, orbit_radius, orbit_radius, 1.5, 5.0, 0.8);
  return world;
}

SyntheticWorld BuildRepetitiveWorld(const WorldParams& params) {
  SyntheticWorld world;
  Scene& scene = world.scene;
  TextureFactory textures(&scene, params, 1);
  SyntheticRandom rng(SyntheticRandom::Mix(params.seed, 3));
  const double tile = 1.6;
  const double half_w = 3.0 * tile;  // 6 x 4 tiles footprint, 4 tiles high
  const double half_d = 2.0 * tile;
  const double height = 4.0 * tile;
  const double margin = 7.5;
  const double g = half_w + margin + 6.0;
  AddGround(&scene, &textures, g);
  AddBackgroundRing(&scene, &textures, g, 6.0, 3);
  const int window = textures.WindowTile(256);
  scene.AddBox(Eigen::Vector2d::Zero(),
               Eigen::Vector2d(2 * half_w, 2 * half_d),
               0.0,
               0.0,
               height,
               {window},
               textures.Smooth(256),
               tile);

  world.target = Eigen::Vector3d(0, 0, 0.45 * height);
  world.cameras = OrbitCameras(params,
                               &rng,
                               world.target,
                               half_w + margin,
                               half_d + margin,
                               1.5,
                               4.0,
                               0.8);
  return world;
}

SyntheticWorld BuildTwinPrintWorld(const WorldParams& params) {
  SyntheticWorld world;
  Scene& scene = world.scene;
  TextureFactory textures(&scene, params, 1);
  SyntheticRandom rng(SyntheticRandom::Mix(params.seed, 5));
  const double orbit_radius = 8.0;
  const double g = orbit_radius + 6.0;
  AddGround(&scene, &textures, g);
  // The room: every wall segment its own texture, the only thing that tells
  // the front views from the back views.
  AddBackgroundRing(&scene, &textures, g, 6.0, 3);
  // The object: one print on the front and the back, one plain finish on
  // both ends, on a plain plinth: a 180-degree turn maps it onto itself.
  const int print = textures.Random(1024, 1024);
  const int end = textures.Smooth(256);
  const double width = rng.Uniform(3.5, 4.5);
  const double depth = rng.Uniform(1.2, 1.8);
  const double height = rng.Uniform(3.0, 4.0);
  scene.AddBox(Eigen::Vector2d::Zero(),
               Eigen::Vector2d(width, depth),
               rng.Uniform(0.0, M_PI),
               0.0,
               height,
               {print, end, print, end},
               textures.Smooth(256),
               0.0);
  world.target = Eigen::Vector3d(0, 0, 0.5 * height);
  world.cameras = OrbitCameras(
      params, &rng, world.target, orbit_radius, orbit_radius, 1.5, 3.5, 0.3);
  return world;
}

SyntheticWorld BuildTwinObjectsWorld(const WorldParams& params) {
  SyntheticWorld world;
  Scene& scene = world.scene;
  TextureFactory textures(&scene, params, 1);
  SyntheticRandom rng(SyntheticRandom::Mix(params.seed, 6));
  const double g = 14.0;
  AddGround(&scene, &textures, g);
  AddBackgroundRing(&scene, &textures, g, 6.0, 3);
  // The table: unique top and sides.
  const double table_height = 1.0;
  const double table_width = 9.0;
  scene.AddBox(Eigen::Vector2d::Zero(),
               Eigen::Vector2d(table_width, 3.0),
               0.0,
               0.0,
               table_height,
               {textures.Random(512, 256),
                textures.Random(256, 256),
                textures.Random(512, 256),
                textures.Random(256, 256)},
               textures.Random(1024, 512),
               0.0);
  // The two copies: one set of textures, one size, one yaw.
  const std::vector<int> sides = {textures.Random(512, 512),
                                  textures.Random(512, 512),
                                  textures.Random(512, 512),
                                  textures.Random(512, 512)};
  const int top = textures.Random(256, 256);
  const Eigen::Vector2d size(rng.Uniform(1.2, 1.6), rng.Uniform(0.8, 1.2));
  const double height = rng.Uniform(1.2, 1.8);
  const double yaw = rng.Uniform(-0.3, 0.3);
  const double half_spacing = rng.Uniform(2.5, 3.0);
  for (const double x : {-half_spacing, half_spacing}) {
    scene.AddBox(Eigen::Vector2d(x, 0.0),
                 size,
                 yaw,
                 table_height,
                 height,
                 sides,
                 top,
                 0.0);
  }
  // The arc: in front of the table (negative y), close enough that a view
  // holds little more than one copy; the first half of the cameras look at
  // the first copy, the second half at the second.
  const int n = params.num_images;
  const double arc = rng.Uniform(0.45, 0.55) * M_PI;
  const double radius = rng.Uniform(4.0, 4.5);
  for (int i = 0; i < n; ++i) {
    const double a = n > 1 ? static_cast<double>(i) / (n - 1) : 0.5;
    const double jitter = rng.Uniform(-0.25, 0.25) / std::max(1, n - 1);
    const double angle = -0.5 * M_PI + (a + jitter - 0.5) * arc;
    const Eigen::Vector3d center(radius * std::cos(angle),
                                 radius * std::sin(angle),
                                 rng.Uniform(2.0, 2.8));
    const double copy_x = 2 * i < n ? -half_spacing : half_spacing;
    const Eigen::Vector3d look_at(
        copy_x + rng.Uniform(-0.3, 0.3),
        rng.Uniform(-0.3, 0.3),
        table_height + 0.5 * height + rng.Uniform(-0.2, 0.2));
    world.cameras.push_back(LookAtCamera(center,
                                         look_at,
                                         rng.Uniform(-0.05, 0.05),
                                         params.width,
                                         params.height,
                                         params.focal_length));
  }
  world.target = Eigen::Vector3d(0, 0, table_height + 0.5 * height);
  return world;
}

namespace {

// The symmetric world's tiered tower, from height z up: n-sided walls,
// soffits and roofs, identical on every side.
void AddSymmetricTiers(
    int n, double phase, double z, TextureFactory* textures, Scene* scene) {
  // Tiers: wall radius, wall top, roof rim radius, roof top radius, roof top
  // height (the next tier's wall starts there).
  struct Tier {
    double wall_radius, wall_top, rim_radius, top_radius, top_z;
  };
  const Tier tiers[] = {{4.0, 3.6, 4.8, 3.0, 4.6},
                        {3.0, 6.2, 3.7, 1.8, 7.0},
                        {1.8, 8.2, 2.4, 0.0, 9.6}};
  const int soffit_tex = textures->Smooth(256);
  for (const Tier& tier : tiers) {
    const int wall_tex = textures->Random(1024, 1024);
    const int roof_tex = textures->Random(1024, 512);
    scene->AddPrism(RegularPolygon(n, tier.wall_radius, phase),
                    z,
                    tier.wall_top,
                    {wall_tex},
                    -1,
                    0.0);
    const auto wall = RegularPolygon(n, tier.wall_radius, phase);
    const auto rim = RegularPolygon(n, tier.rim_radius, phase);
    const auto top = RegularPolygon(n, tier.top_radius, phase);
    const double zr = tier.wall_top;
    for (int k = 0; k < n; ++k) {
      const int k1 = (k + 1) % n;
      // Soffit under the overhang (facing down).
      scene->AddQuad(Eigen::Vector3d(rim[k1].x(), rim[k1].y(), zr),
                     Eigen::Vector3d(rim[k].x(), rim[k].y(), zr),
                     Eigen::Vector3d(wall[k].x(), wall[k].y(), zr),
                     Eigen::Vector3d(wall[k1].x(), wall[k1].y(), zr),
                     soffit_tex);
      if (tier.top_radius > 0.0) {
        scene->AddQuad(Eigen::Vector3d(rim[k].x(), rim[k].y(), zr),
                       Eigen::Vector3d(rim[k1].x(), rim[k1].y(), zr),
                       Eigen::Vector3d(top[k1].x(), top[k1].y(), tier.top_z),
                       Eigen::Vector3d(top[k].x(), top[k].y(), tier.top_z),
                       roof_tex);
      }
    }
    if (tier.top_radius <= 0.0) {
      std::vector<Eigen::Vector3d> rim3;
      for (const auto& p : rim) rim3.emplace_back(p.x(), p.y(), zr);
      scene->AddFan(Eigen::Vector3d(0, 0, tier.top_z), rim3, roof_tex, 2.0);
    }
    z = tier.top_z;
  }
}

// What breaks the symmetric world's symmetry: a plaque on one side of the
// lowest wall and two unique objects on the ground.
void AddSymmetryBreakingDetails(int n,
                                TextureFactory* textures,
                                SyntheticRandom* rng,
                                Scene* scene) {
  // A plaque on one side of the lowest wall, just in front of it.
  const double apothem = 4.0 * std::cos(M_PI / n) + 0.02;
  const double half = 0.6;
  const Eigen::Vector2d normal(1.0, 0.0);  // the side facing +x
  const Eigen::Vector2d tangent(0.0, 1.0);
  const Eigen::Vector2d c = apothem * normal;
  const Eigen::Vector2d a = c - half * tangent;
  const Eigen::Vector2d b = c + half * tangent;
  scene->AddQuad(Eigen::Vector3d(a.x(), a.y(), 1.9),
                 Eigen::Vector3d(b.x(), b.y(), 1.9),
                 Eigen::Vector3d(b.x(), b.y(), 2.8),
                 Eigen::Vector3d(a.x(), a.y(), 2.8),
                 textures->Random(256, 256));
  // Two unique objects on the ground.
  for (int d = 0; d < 2; ++d) {
    const double angle = rng->Uniform(0.0, 2.0 * M_PI);
    std::vector<int> sides;
    for (int k = 0; k < 4; ++k) sides.push_back(textures->Random(256, 256));
    scene->AddBox(8.5 * Eigen::Vector2d(std::cos(angle), std::sin(angle)),
                  Eigen::Vector2d(0.9, 0.9),
                  angle,
                  0.0,
                  1.2,
                  sides,
                  textures->Random(128, 128),
                  0.0);
  }
}

}  // namespace

SyntheticWorld BuildSymmetricWorld(const WorldParams& params) {
  SyntheticWorld world;
  Scene& scene = world.scene;
  TextureFactory textures(&scene, params, 1);
  SyntheticRandom rng(SyntheticRandom::Mix(params.seed, 4));
  const int n = std::max(3, params.symmetric_sides);
  world.num_symmetric_sides = n;
  scene.light_direction = Eigen::Vector3d::UnitZ();  // keeps the symmetry
  const double orbit_radius = 16.0;
  const double g = orbit_radius + 6.0;
  // Phase so that a side (not a corner) faces the +x axis.
  const double phase = M_PI / n;

  // Ground: n congruent wedges with identical texturing.
  {
    const int tex = textures.Random(2048, 2048);
    std::vector<Eigen::Vector3d> rim;
    for (const auto& p : RegularPolygon(n, g, phase)) {
      rim.emplace_back(p.x(), p.y(), 0.0);
    }
    scene.AddFan(Eigen::Vector3d::Zero(), rim, tex, g);
  }
  // Background ring: 2 segments per side, the same two textures per side.
  {
    const int tex_a = textures.Random(1024, 512);
    const int tex_b = textures.Random(1024, 512);
    std::vector<Eigen::Vector2d> footprint = RegularPolygon(2 * n, g, phase);
    std::reverse(footprint.begin(), footprint.end());  // face inwards
    // Reversal maps segment k to k' = 2n - 2 - k, keep pairs aligned.
    scene.AddPrism(footprint, 0.0, 6.0, {tex_a, tex_b}, -1, 0.0);
  }
  // Terraces.
  const int terrace_tex = textures.Random(1024, 256);
  const int terrace_top = textures.Random(1024, 1024);
  double z = 0.0;
  for (const double radius : {7.0, 6.2, 5.4}) {
    scene.AddPrism(RegularPolygon(n, radius, phase),
                   z,
                   z + 0.4,
                   {terrace_tex},
                   terrace_top,
                   0.0);
    z += 0.4;
  }
  AddSymmetricTiers(n, phase, z, &textures, &scene);
  if (params.add_details) {
    AddSymmetryBreakingDetails(n, &textures, &rng, &scene);
  }

  world.target = Eigen::Vector3d(0, 0, 4.0);
  world.cameras = OrbitCameras(
      params, &rng, world.target, orbit_radius, orbit_radius, 1.5, 6.0, 0.8);
  return world;
}

SyntheticWorld BuildDistractorWorld(const WorldParams& params) {
  SyntheticWorld world;
  Scene& scene = world.scene;
  TextureFactory textures(&scene, params, 11);
  SyntheticRandom rng(SyntheticRandom::Mix(params.seed, 12));
  const double g = 12.0;
  const int ground = textures.Random(1024, 1024);
  scene.AddQuad(Eigen::Vector3d(-g, -g, 0),
                Eigen::Vector3d(g, -g, 0),
                Eigen::Vector3d(g, g, 0),
                Eigen::Vector3d(-g, g, 0),
                ground);
  const int num_boxes = rng.UniformInt(2, 3);
  for (int b = 0; b < num_boxes; ++b) {
    std::vector<int> sides;
    for (int k = 0; k < 4; ++k) sides.push_back(textures.Random(512, 512));
    scene.AddBox(Eigen::Vector2d(rng.Uniform(-3, 3), rng.Uniform(-3, 3)),
                 Eigen::Vector2d(rng.Uniform(1.5, 4), rng.Uniform(1.5, 4)),
                 rng.Uniform(0, M_PI),
                 0.0,
                 rng.Uniform(1.5, 4),
                 sides,
                 textures.Random(256, 256),
                 0.0);
  }
  world.target = Eigen::Vector3d(0, 0, 1.0);
  world.cameras =
      OrbitCameras(params, &rng, world.target, 9.0, 9.0, 1.5, 3.0, 1.0);
  return world;
}

}  // namespace colmap_gcn
