#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <opencv2/imgcodecs.hpp>

#include "scene/reconstruction.h"
#include "synthetic/camera.h"
#include "synthetic/pair_overlap.h"
#include "synthetic/renderer.h"
#include "synthetic/scene.h"
#include "synthetic/scene_families.h"
#include "synthetic/scene_generator.h"
#include "synthetic/surface_samples.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"

namespace colmap_gcn {
namespace {

std::string FileBytes(const std::string& path) { return ReadTextFile(path); }

SyntheticSceneOptions SmallOptions() {
  SyntheticSceneOptions options;
  options.num_images = 5;
  options.num_distractors = 1;
  options.width = 160;
  options.height = 120;
  options.num_surface_samples = 4000;
  options.seed = 3;
  return options;
}

TEST(SyntheticSceneOptions, CheckRejectsBadValues) {
  SyntheticSceneOptions options;
  EXPECT_NO_THROW(options.Check());
  auto expect_bad = [](auto mutate) {
    SyntheticSceneOptions bad;
    mutate(&bad);
    EXPECT_THROW(bad.Check(), OptionError);
    TemporaryDirectory dir;
    EXPECT_THROW(GenerateSyntheticScene(bad, dir.Path()), Error);
  };
  expect_bad([](SyntheticSceneOptions* o) { o->family = "gothic"; });
  expect_bad([](SyntheticSceneOptions* o) { o->num_images = 1; });
  expect_bad([](SyntheticSceneOptions* o) { o->num_distractors = -1; });
  expect_bad([](SyntheticSceneOptions* o) { o->width = 0; });
  expect_bad([](SyntheticSceneOptions* o) { o->height = 8; });
  expect_bad([](SyntheticSceneOptions* o) { o->focal_length_factor = 0; });
  expect_bad([](SyntheticSceneOptions* o) { o->seed = -5; });
  expect_bad([](SyntheticSceneOptions* o) { o->num_surface_samples = 0; });
  expect_bad([](SyntheticSceneOptions* o) { o->symmetric_sides = 2; });
  expect_bad([](SyntheticSceneOptions* o) { o->min_view_cosine = 1.0; });
  expect_bad([](SyntheticSceneOptions* o) { o->jpeg_quality = 0; });
}

TEST(SyntheticSceneOptions, MissingTextureDirIsAnError) {
  SyntheticSceneOptions options = SmallOptions();
  options.texture_dir = "/nonexistent/textures";
  TemporaryDirectory dir;
  EXPECT_THROW(GenerateSyntheticScene(options, dir.Path()), Error);
}

TEST(PinholeCamera, HandCheckedProjection) {
  // Camera at (0, -10, 0) looking at the origin along +y, world up +z:
  // camera x = world x, camera y (down) = world -z, camera z = world y.
  const PinholeCamera camera = LookAtCamera(Eigen::Vector3d(0, -10, 0),
                                            Eigen::Vector3d::Zero(),
                                            0.0,
                                            640,
                                            480,
                                            500.0);
  Eigen::Vector2d xy;
  ASSERT_TRUE(camera.Project(Eigen::Vector3d(0, 0, 0), &xy));
  EXPECT_NEAR(xy.x(), 320.0, 1e-9);
  EXPECT_NEAR(xy.y(), 240.0, 1e-9);
  ASSERT_TRUE(camera.Project(Eigen::Vector3d(1, 0, 0), &xy));
  EXPECT_NEAR(xy.x(), 320.0 + 500.0 * 1.0 / 10.0, 1e-9);
  EXPECT_NEAR(xy.y(), 240.0, 1e-9);
  ASSERT_TRUE(camera.Project(Eigen::Vector3d(0, 10, 2), &xy));
  EXPECT_NEAR(xy.x(), 320.0, 1e-9);
  EXPECT_NEAR(xy.y(), 240.0 - 500.0 * 2.0 / 20.0, 1e-9);
  EXPECT_FALSE(camera.Project(Eigen::Vector3d(0, -20, 0), &xy));
  EXPECT_TRUE(camera.Center().isApprox(Eigen::Vector3d(0, -10, 0)));
  // qvec (w, x, y, z) reproduces R.
  const Eigen::Vector4d q = camera.Qvec();
  const Eigen::Matrix3d R =
      Eigen::Quaterniond(q(0), q(1), q(2), q(3)).toRotationMatrix();
  EXPECT_TRUE(R.isApprox(camera.R, 1e-12));
  // The ray through a pixel centre passes through the point projecting there.
  const Eigen::Vector3d dir = camera.RayDirection(370.0, 240.0);
  EXPECT_TRUE(dir.isApprox(Eigen::Vector3d(1, 10, 0).normalized(), 1e-12));
}

// A scene with one uniformly coloured quad, rendered without photometric
// variation: the pixel whose centre projects from inside the quad has its
// colour, pixels outside show the sky.
TEST(Renderer, QuadAppearsWhereTheCameraProjectsIt) {
  Scene scene;
  TextureSpec spec;
  spec.kind = TextureSpec::Kind::kUser;
  spec.user_index = 0;
  const int tex = scene.AddTexture(spec);
  scene.ambient = 1.0f;
  scene.diffuse = 0.0f;
  // Quad in the plane y = 0 facing -y, x in [-1, 1], z in [-0.5, 0.5].
  scene.AddQuad(Eigen::Vector3d(-1, 0, -0.5),
                Eigen::Vector3d(1, 0, -0.5),
                Eigen::Vector3d(1, 0, 0.5),
                Eigen::Vector3d(-1, 0, 0.5),
                tex);
  scene.GenerateTextures({cv::Mat(8, 8, CV_8UC3, cv::Scalar(10, 20, 200))}, 1);
  const PinholeCamera camera = LookAtCamera(Eigen::Vector3d(0, -10, 0),
                                            Eigen::Vector3d::Zero(),
                                            0.0,
                                            640,
                                            480,
                                            500.0);
  const cv::Mat image = RenderImage(scene, camera, PhotometricParams());
  // Corner (1, 0, 0.5) projects to (370, 215): pixel (369, 215) has its
  // centre at (369.5, 215.5), inside; pixel (371, 214) is outside.
  Eigen::Vector2d corner;
  ASSERT_TRUE(camera.Project(Eigen::Vector3d(1, 0, 0.5), &corner));
  EXPECT_NEAR(corner.x(), 370.0, 1e-9);
  EXPECT_NEAR(corner.y(), 215.0, 1e-9);
  const cv::Vec3b inside = image.at<cv::Vec3b>(215, 369);
  EXPECT_EQ(inside, cv::Vec3b(10, 20, 200));
  const cv::Vec3b outside_right = image.at<cv::Vec3b>(240, 370);
  const cv::Vec3b outside_top = image.at<cv::Vec3b>(214, 360);
  EXPECT_NE(outside_right, cv::Vec3b(10, 20, 200));
  EXPECT_NE(outside_top, cv::Vec3b(10, 20, 200));
  EXPECT_EQ(image.at<cv::Vec3b>(240, 320), cv::Vec3b(10, 20, 200));
}

TEST(SurfaceSamples, VisibilityHandlesOcclusionFacingAndFrustum) {
  Scene scene;
  TextureSpec spec;
  spec.kind = TextureSpec::Kind::kUser;
  spec.user_index = 0;
  const int tex = scene.AddTexture(spec);
  // Back wall at y = 5 facing -y (x in [-4, 4], z in [-3, 3]), and a small
  // occluder at y = 0 facing -y (x, z in [-1, 1]).
  scene.AddQuad(Eigen::Vector3d(-4, 5, -3),
                Eigen::Vector3d(4, 5, -3),
                Eigen::Vector3d(4, 5, 3),
                Eigen::Vector3d(-4, 5, 3),
                tex);
  scene.AddQuad(Eigen::Vector3d(-1, 0, -1),
                Eigen::Vector3d(1, 0, -1),
                Eigen::Vector3d(1, 0, 1),
                Eigen::Vector3d(-1, 0, 1),
                tex);
  scene.GenerateTextures({cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(128))}, 1);
  const std::vector<SurfaceSample> samples = SampleSurfaces(scene, 5000, 1);
  ASSERT_EQ(samples.size(), 5000u);

  const PinholeCamera front = LookAtCamera(Eigen::Vector3d(0, -10, 0),
                                           Eigen::Vector3d::Zero(),
                                           0.0,
                                           640,
                                           480,
                                           300.0);
  const std::vector<SampleObservation> visible = ComputeVisibleSamples(
      scene, TriangleBins(scene, front), front, samples, 0.0);
  std::set<int> visible_set;
  for (const auto& observation : visible) {
    visible_set.insert(observation.sample_idx);
  }
  int num_checked = 0;
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
    const Eigen::Vector3d& X = samples[i].xyz;
    Eigen::Vector2d xy;
    const bool in_image = front.Project(X, &xy) && front.IsInImage(xy);
    bool expected = in_image;
    if (X.y() > 4.0) {
      // On the back wall: hidden iff the ray from the camera passes through
      // the occluder, i.e. the point at y = 0 along it has |x|, |z| < 1.
      const double s = 10.0 / (X.y() + 10.0);
      const bool behind_occluder =
          std::abs(s * X.x()) < 1.0 && std::abs(s * X.z()) < 1.0;
      // Skip samples whose rays graze the occluder's edges.
      if (std::abs(std::abs(s * X.x()) - 1.0) < 1e-6 ||
          std::abs(std::abs(s * X.z()) - 1.0) < 1e-6) {
        continue;
      }
      expected = in_image && !behind_occluder;
    }
    EXPECT_EQ(visible_set.count(i) > 0, expected) << X.transpose();
    ++num_checked;
  }
  EXPECT_GT(num_checked, 4900);
  // Projections are stored for visible samples.
  for (const auto& observation : visible) {
    Eigen::Vector2d xy;
    ASSERT_TRUE(front.Project(samples[observation.sample_idx].xyz, &xy));
    EXPECT_TRUE(xy.isApprox(observation.xy));
  }

  // From behind, nothing faces the camera.
  const PinholeCamera back = LookAtCamera(
      Eigen::Vector3d(0, 20, 0), Eigen::Vector3d::Zero(), 0.0, 640, 480, 300.0);
  EXPECT_TRUE(ComputeVisibleSamples(
                  scene, TriangleBins(scene, back), back, samples, 0.0)
                  .empty());
}

TEST(GenerateSyntheticScene, DeterministicAcrossThreadCounts) {
  const SyntheticSceneOptions options = SmallOptions();
  SyntheticSceneOptions one_thread = options;
  one_thread.num_threads = 1;
  SyntheticSceneOptions two_threads = options;
  two_threads.num_threads = 2;
  SyntheticSceneOptions other_seed = options;
  other_seed.seed = 4;
  TemporaryDirectory a, b, c;
  GenerateSyntheticScene(one_thread, a.Path());
  GenerateSyntheticScene(two_threads, b.Path());
  GenerateSyntheticScene(other_seed, c.Path());
  std::vector<std::string> files = {"gt/cameras.txt",
                                    "gt/images.txt",
                                    "gt/points3D.txt",
                                    "gt/pair_overlap.csv",
                                    "gt/distractors.txt",
                                    "gt/scene.txt",
                                    "images/distractor_0000.jpg"};
  for (int i = 0; i < options.num_images; ++i) {
    files.push_back("images/" + SyntheticImageName(i));
  }
  for (const std::string& file : files) {
    EXPECT_EQ(FileBytes(JoinPaths(a.Path(), file)),
              FileBytes(JoinPaths(b.Path(), file)))
        << file;
  }
  EXPECT_NE(FileBytes(JoinPaths(a.Path(), "images/synth_0000.jpg")),
            FileBytes(JoinPaths(c.Path(), "images/synth_0000.jpg")));
  EXPECT_NE(FileBytes(JoinPaths(a.Path(), "gt/images.txt")),
            FileBytes(JoinPaths(c.Path(), "gt/images.txt")));
}

// The written model and pair table agree with each other and with the
// projection of the cameras.
TEST(GenerateSyntheticScene, GroundTruthIsConsistent) {
  SyntheticSceneOptions options = SmallOptions();
  options.num_images = 8;
  TemporaryDirectory dir;
  const SyntheticSceneSummary summary =
      GenerateSyntheticScene(options, dir.Path());
  Reconstruction model;
  model.ReadText(JoinPaths(dir.Path(), "gt"));
  ASSERT_EQ(model.cameras.size(), 1u);
  const ModelCamera& camera = model.cameras.begin()->second;
  EXPECT_EQ(camera.model_id, 1);  // PINHOLE
  EXPECT_EQ(camera.width, 160u);
  EXPECT_EQ(camera.height, 120u);
  ASSERT_EQ(camera.params.size(), 4u);
  EXPECT_DOUBLE_EQ(camera.params[0], 160.0);
  EXPECT_DOUBLE_EQ(camera.params[2], 80.0);
  EXPECT_DOUBLE_EQ(camera.params[3], 60.0);
  ASSERT_EQ(model.images.size(), 8u);
  EXPECT_EQ(model.points3D.size(), summary.num_points3D);

  // Every observation is the projection of its point; tracks point back.
  size_t num_observations = 0;
  for (const auto& [image_id, image] : model.images) {
    const Eigen::Matrix3d R = image.RotationMatrix();
    for (size_t k = 0; k < image.points2D.size(); ++k) {
      const ModelPoint3D& point = model.points3D.at(image.point3D_ids[k]);
      const Eigen::Vector3d p = R * point.xyz + image.tvec;
      ASSERT_GT(p.z(), 0.0);
      const Eigen::Vector2d xy(
          camera.params[0] * p.x() / p.z() + camera.params[2],
          camera.params[1] * p.y() / p.z() + camera.params[3]);
      EXPECT_LT((xy - image.points2D[k]).norm(), 1e-6);
      EXPECT_GE(xy.x(), 0.0);
      EXPECT_LT(xy.x(), 160.0);
      bool in_track = false;
      for (const TrackElement& element : point.track) {
        in_track |= element.image_id == image_id && element.point2D_idx == k;
      }
      EXPECT_TRUE(in_track);
      ++num_observations;
    }
  }
  EXPECT_EQ(num_observations, summary.num_observations);

  // Pair table: one row per unordered pair (distractor included), counts
  // agree with the tracks, overlaps are shared / visible both ways.
  const PairOverlapTable table =
      ReadPairOverlapTable(JoinPaths(dir.Path(), "gt/pair_overlap.csv"));
  EXPECT_EQ(table.NumPairs(), 9u * 8u / 2u);
  std::map<std::pair<image_t, image_t>, int> shared;
  for (const auto& [point_id, point] : model.points3D) {
    for (size_t a = 0; a < point.track.size(); ++a) {
      for (size_t b = a + 1; b < point.track.size(); ++b) {
        const image_t i =
            std::min(point.track[a].image_id, point.track[b].image_id);
        const image_t j =
            std::max(point.track[a].image_id, point.track[b].image_id);
        ++shared[{i, j}];
      }
    }
  }
  int num_positive = 0;
  for (const PairOverlap& pair : table.Pairs()) {
    const image_t i = model.FindImageWithName(pair.name1);
    const image_t j = model.FindImageWithName(pair.name2);
    if (pair.name2 == DistractorImageName(0)) {
      EXPECT_EQ(j, kInvalidImageId);
      EXPECT_EQ(pair.num_shared, 0);
      EXPECT_EQ(pair.overlap12, 0.0);
      EXPECT_EQ(pair.overlap21, 0.0);
      continue;
    }
    ASSERT_NE(i, kInvalidImageId);
    ASSERT_NE(j, kInvalidImageId);
    const std::pair<image_t, image_t> key(std::min(i, j), std::max(i, j));
    EXPECT_EQ(pair.num_shared, shared[key]);
    EXPECT_EQ(pair.num_visible1,
              static_cast<int>(model.images.at(i).points2D.size()));
    EXPECT_EQ(pair.num_visible2,
              static_cast<int>(model.images.at(j).points2D.size()));
    EXPECT_NEAR(pair.overlap12 * pair.num_visible1, pair.num_shared, 1e-3);
    EXPECT_NEAR(pair.overlap21 * pair.num_visible2, pair.num_shared, 1e-3);
    EXPECT_DOUBLE_EQ(table.Overlap(pair.name1, pair.name2), pair.overlap12);
    EXPECT_DOUBLE_EQ(table.Overlap(pair.name2, pair.name1), pair.overlap21);
    num_positive += pair.num_shared > 0;
  }
  EXPECT_GT(num_positive, 0);
  EXPECT_EQ(ReadTextFile(JoinPaths(dir.Path(), "gt/distractors.txt")),
            DistractorImageName(0) + "\n");
}

TEST(SceneFamilies, SymmetricTempleHasIdenticalSides) {
  WorldParams params;
  params.num_images = 4;
  params.width = 200;
  params.height = 150;
  params.focal_length = 200;
  params.symmetric_sides = 6;
  params.add_details = false;
  SyntheticWorld world = BuildSymmetricWorld(params);
  EXPECT_EQ(world.num_symmetric_sides, 6);
  // Geometry: rotating every triangle by 2 pi / 6 about z gives a triangle
  // of the scene with the same texture and texture coordinates.
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(2.0 * M_PI / 6, Eigen::Vector3d::UnitZ())
          .toRotationMatrix();
  for (const SceneTriangle& tri : world.scene.triangles) {
    bool found = false;
    for (const SceneTriangle& other : world.scene.triangles) {
      if (other.texture_id == tri.texture_id &&
          (other.v0 - rotation * tri.v0).norm() < 1e-9 &&
          (other.e1 - rotation * tri.e1).norm() < 1e-9 &&
          (other.e2 - rotation * tri.e2).norm() < 1e-9 &&
          (other.uv0 - tri.uv0).norm() < 1e-9 &&
          (other.duv1 - tri.duv1).norm() < 1e-9 &&
          (other.duv2 - tri.duv2).norm() < 1e-9) {
        found = true;
        break;
      }
    }
    ASSERT_TRUE(found) << "triangle at " << tri.v0.transpose()
                       << " has no rotated copy";
  }
  // Appearance: views rotated by one side look the same.
  world.scene.GenerateTextures({}, 2);
  const PinholeCamera a = LookAtCamera(Eigen::Vector3d(16, 0, 3),
                                       Eigen::Vector3d(0, 0, 4),
                                       0.0,
                                       200,
                                       150,
                                       200.0);
  const Eigen::Vector3d rotated_center = rotation * Eigen::Vector3d(16, 0, 3);
  const PinholeCamera b = LookAtCamera(
      rotated_center, Eigen::Vector3d(0, 0, 4), 0.0, 200, 150, 200.0);
  const cv::Mat image_a = RenderImage(world.scene, a, PhotometricParams());
  const cv::Mat image_b = RenderImage(world.scene, b, PhotometricParams());
  cv::Mat diff;
  cv::absdiff(image_a, image_b, diff);
  EXPECT_LT(cv::mean(diff)[0] + cv::mean(diff)[1] + cv::mean(diff)[2], 1.5);

  // With the details the symmetry is broken somewhere.
  params.add_details = true;
  const SyntheticWorld detailed = BuildSymmetricWorld(params);
  EXPECT_GT(detailed.scene.triangles.size(), world.scene.triangles.size());
}

TEST(SceneFamilies, RepetitiveFacadesShareOneTileTexture) {
  WorldParams params;
  const SyntheticWorld world = BuildRepetitiveWorld(params);
  std::map<int, int> window_triangles;
  for (const SceneTriangle& tri : world.scene.triangles) {
    if (world.scene.texture_specs[tri.texture_id].kind ==
        TextureSpec::Kind::kWindowTile) {
      ++window_triangles[tri.texture_id];
      // Several whole tiles per facade.
      EXPECT_GE(std::max(std::abs(tri.duv1.x()), std::abs(tri.duv2.x())), 3.0);
    }
  }
  ASSERT_EQ(window_triangles.size(), 1u);
  EXPECT_EQ(window_triangles.begin()->second, 8);  // 4 facades
  EXPECT_EQ(static_cast<int>(world.cameras.size()), params.num_images);
}

TEST(SceneFamilies, TwinObjectsAreTranslatedCopiesSeenFromAnArc) {
  WorldParams params;
  params.num_images = 12;
  params.seed = 3;
  const SyntheticWorld world = BuildTwinObjectsWorld(params);
  // Every triangle of the first copy has a translated twin with the same
  // texture and texture coordinates: the copies are indistinguishable.
  std::map<int, int> triangles_per_texture;
  for (const SceneTriangle& tri : world.scene.triangles) {
    ++triangles_per_texture[tri.texture_id];
  }
  int num_matched = 0;
  for (const SceneTriangle& tri : world.scene.triangles) {
    if (tri.v0.x() >= 0 || triangles_per_texture[tri.texture_id] < 4) continue;
    for (const SceneTriangle& other : world.scene.triangles) {
      const Eigen::Vector3d shift = other.v0 - tri.v0;
      if (other.texture_id == tri.texture_id && shift.x() > 1.0 &&
          std::abs(shift.y()) < 1e-9 && std::abs(shift.z()) < 1e-9 &&
          (other.e1 - tri.e1).norm() < 1e-9 &&
          (other.e2 - tri.e2).norm() < 1e-9 &&
          (other.uv0 - tri.uv0).norm() < 1e-9) {
        ++num_matched;
        break;
      }
    }
  }
  // Four sides (two triangles each) and the top (a fan of four).
  EXPECT_EQ(num_matched, 12);
  // The cameras sweep in front of the table (negative y), left to right;
  // the first half looks at the first copy (x < 0), the second half at the
  // second.
  ASSERT_EQ(static_cast<int>(world.cameras.size()), params.num_images);
  for (size_t i = 0; i < world.cameras.size(); ++i) {
    const Eigen::Vector3d center = world.cameras[i].Center();
    EXPECT_LT(center.y(), -2.0);
    if (i > 0) {
      EXPECT_GT(center.x(), world.cameras[i - 1].Center().x());
    }
    const Eigen::Vector3d axis = world.cameras[i].R.row(2).transpose();
    ASSERT_GT(axis.y(), 0.0);
    const double x_at_copies = center.x() - center.y() / axis.y() * axis.x();
    if (2 * i < world.cameras.size()) {
      EXPECT_LT(x_at_copies, -1.0) << "camera " << i;
    } else {
      EXPECT_GT(x_at_copies, 1.0) << "camera " << i;
    }
  }
}

TEST(PairOverlapTable, RoundTripAndErrors) {
  PairOverlapTable table;
  PairOverlap pair;
  pair.name1 = "a.jpg";
  pair.name2 = "b.jpg";
  pair.num_visible1 = 10;
  pair.num_visible2 = 20;
  pair.num_shared = 5;
  pair.overlap12 = 0.5;
  pair.overlap21 = 0.25;
  table.Add(pair);
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "pairs.csv");
  WritePairOverlapTable(table, path);
  const PairOverlapTable read = ReadPairOverlapTable(path);
  ASSERT_EQ(read.NumPairs(), 1u);
  EXPECT_EQ(read.Pairs()[0].num_shared, 5);
  EXPECT_DOUBLE_EQ(read.Overlap("a.jpg", "b.jpg"), 0.5);
  EXPECT_DOUBLE_EQ(read.Overlap("b.jpg", "a.jpg"), 0.25);
  EXPECT_DOUBLE_EQ(read.Overlap("a.jpg", "c.jpg"), 0.0);
  ASSERT_NE(read.Find("b.jpg", "a.jpg"), nullptr);
  EXPECT_DOUBLE_EQ(read.Find("b.jpg", "a.jpg")->MinOverlap(), 0.25);

  EXPECT_THROW(ReadPairOverlapTable(JoinPaths(dir.Path(), "missing.csv")),
               Error);
  const std::string bad = JoinPaths(dir.Path(), "bad.csv");
  WriteFileAtomically(bad, "a,b\n");
  EXPECT_THROW(ReadPairOverlapTable(bad), Error);
  WriteFileAtomically(bad,
                      "name1,name2,num_visible1,num_visible2,num_shared,"
                      "overlap12,overlap21\na.jpg,b.jpg,1,2,x,0.5,0.5\n");
  EXPECT_THROW(ReadPairOverlapTable(bad), Error);
  WriteFileAtomically(bad,
                      "name1,name2,num_visible1,num_visible2,num_shared,"
                      "overlap12,overlap21\na.jpg,b.jpg,1,2,1,1.5,0.5\n");
  EXPECT_THROW(ReadPairOverlapTable(bad), Error);
}

}  // namespace
}  // namespace colmap_gcn
