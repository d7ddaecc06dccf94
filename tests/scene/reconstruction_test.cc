#include "scene/reconstruction.h"

#include <cmath>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "scene/camera_models.h"
#include "scene/model_writer.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

// Two cameras, three images with random poses and observations, points whose
// tracks are consistent with the images' point3D ids (so that COLMAP accepts
// the model). Awkward doubles check that text output is full precision.
Reconstruction MakeModel() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Reconstruction model;

  ModelCamera pinhole;
  pinhole.camera_id = 1;
  pinhole.model_id = CameraModelNameToId("PINHOLE");
  pinhole.width = 1536;
  pinhole.height = 1024;
  pinhole.params = {1379.74 + 1.0 / 3.0, 1382.08, 760.095, 503.155};
  model.cameras[1] = pinhole;
  ModelCamera radial;
  radial.camera_id = 7;
  radial.model_id = CameraModelNameToId("SIMPLE_RADIAL");
  radial.width = 640;
  radial.height = 480;
  radial.params = {500.1, 320, 240, -0.0123456789012345678};
  model.cameras[7] = radial;

  for (const image_t image_id : {2u, 5u, 9u}) {
    ModelImage image;
    image.image_id = image_id;
    image.qvec = Eigen::Vector4d(
                     1 + uniform(rng), uniform(rng), uniform(rng), uniform(rng))
                     .normalized();
    image.tvec = Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng)) * 3;
    image.camera_id = image_id == 9 ? 7 : 1;
    image.name = "img_" + std::to_string(image_id) + ".jpg";
    for (int j = 0; j < 5; ++j) {
      image.points2D.emplace_back(100 * std::abs(uniform(rng)) + 0.1,
                                  100 * std::abs(uniform(rng)) + 1e-9);
      image.point3D_ids.push_back(kInvalidPoint3DId);
    }
    model.images[image_id] = image;
  }

  // Point p is seen by observation p of every image.
  for (point3D_t point3D_id = 1; point3D_id <= 4; ++point3D_id) {
    ModelPoint3D point;
    point.xyz = Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng) + 5);
    point.color << 255, static_cast<uint8_t>(point3D_id * 40), 0;
    point.error = 0.25 * point3D_id + 1e-12;
    for (auto& [image_id, image] : model.images) {
      const point2D_t idx = static_cast<point2D_t>(point3D_id - 1);
      image.point3D_ids[idx] = point3D_id;
      point.track.push_back({image_id, idx});
    }
    model.points3D[point3D_id] = point;
  }
  return model;
}

void ExpectModelsEqual(const Reconstruction& a, const Reconstruction& b) {
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (const auto& [camera_id, camera] : a.cameras) {
    ASSERT_EQ(b.cameras.count(camera_id), 1u) << camera_id;
    const ModelCamera& other = b.cameras.at(camera_id);
    EXPECT_EQ(camera.camera_id, other.camera_id);
    EXPECT_EQ(camera.model_id, other.model_id);
    EXPECT_EQ(camera.width, other.width);
    EXPECT_EQ(camera.height, other.height);
    EXPECT_EQ(camera.params, other.params);
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (const auto& [image_id, image] : a.images) {
    ASSERT_EQ(b.images.count(image_id), 1u) << image_id;
    const ModelImage& other = b.images.at(image_id);
    EXPECT_EQ(image.image_id, other.image_id);
    EXPECT_EQ(image.qvec, other.qvec);
    EXPECT_EQ(image.tvec, other.tvec);
    EXPECT_EQ(image.camera_id, other.camera_id);
    EXPECT_EQ(image.name, other.name);
    EXPECT_EQ(image.points2D, other.points2D);
    EXPECT_EQ(image.point3D_ids, other.point3D_ids);
  }
  ASSERT_EQ(a.points3D.size(), b.points3D.size());
  for (const auto& [point3D_id, point] : a.points3D) {
    ASSERT_EQ(b.points3D.count(point3D_id), 1u) << point3D_id;
    const ModelPoint3D& other = b.points3D.at(point3D_id);
    EXPECT_EQ(point.xyz, other.xyz);
    EXPECT_EQ(point.color, other.color);
    EXPECT_EQ(point.error, other.error);
    ASSERT_EQ(point.track.size(), other.track.size());
    for (size_t i = 0; i < point.track.size(); ++i) {
      EXPECT_EQ(point.track[i].image_id, other.track[i].image_id);
      EXPECT_EQ(point.track[i].point2D_idx, other.track[i].point2D_idx);
    }
  }
}

void ExpectErrorNaming(const std::function<void()>& function,
                       const std::string& path) {
  try {
    function();
    ADD_FAILURE() << "expected an Error naming " << path;
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(CameraModels, IdsNamesAndParamCounts) {
  const std::vector<std::pair<std::string, int>> expected = {
      {"SIMPLE_PINHOLE", 3},
      {"PINHOLE", 4},
      {"SIMPLE_RADIAL", 4},
      {"RADIAL", 5},
      {"OPENCV", 8},
      {"OPENCV_FISHEYE", 8},
      {"FULL_OPENCV", 12},
      {"FOV", 5},
      {"SIMPLE_RADIAL_FISHEYE", 4},
      {"RADIAL_FISHEYE", 5},
      {"THIN_PRISM_FISHEYE", 12}};
  for (size_t id = 0; id < expected.size(); ++id) {
    const int model_id = static_cast<int>(id);
    EXPECT_EQ(CameraModelIdToName(model_id), expected[id].first);
    EXPECT_EQ(CameraModelNameToId(expected[id].first), model_id);
    EXPECT_EQ(CameraModelNumParams(model_id), expected[id].second);
  }
  EXPECT_EQ(CameraModelNameToId("pinhole"), -1);
  EXPECT_EQ(CameraModelIdToName(11), "");
  EXPECT_EQ(CameraModelIdToName(-1), "");
  EXPECT_EQ(CameraModelNumParams(11), -1);
}

TEST(ModelImage, RotationAndProjectionCenter) {
  ModelImage image;
  // 90 degrees about z, not normalized on purpose.
  image.qvec = Eigen::Vector4d(2, 0, 0, 2);
  image.tvec = Eigen::Vector3d(1, 2, 3);
  Eigen::Matrix3d expected;
  expected << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  EXPECT_TRUE(image.RotationMatrix().isApprox(expected));
  const Eigen::Vector3d center = image.ProjectionCenter();
  // The camera centre maps to the camera origin.
  EXPECT_TRUE((image.RotationMatrix() * center + image.tvec).isZero(1e-12));
  EXPECT_TRUE(center.isApprox(Eigen::Vector3d(-2, 1, -3)));

  image.point3D_ids = {kInvalidPoint3DId, 4, 0, kInvalidPoint3DId};
  EXPECT_EQ(image.NumPoints3D(), 2u);
}

TEST(Reconstruction, TextRoundTripIsExact) {
  TemporaryDirectory dir;
  const Reconstruction model = MakeModel();
  model.WriteText(dir.Path());
  Reconstruction read;
  read.ReadText(dir.Path());
  ExpectModelsEqual(model, read);
  Reconstruction read_auto;
  read_auto.Read(dir.Path());
  ExpectModelsEqual(model, read_auto);
  EXPECT_EQ(read.FindImageWithName("img_5.jpg"), 5u);
  EXPECT_EQ(read.FindImageWithName("nope.jpg"), kInvalidImageId);
}

TEST(Reconstruction, BinaryRoundTripIsExact) {
  TemporaryDirectory dir;
  const Reconstruction model = MakeModel();
  test::WriteBinaryModel(model, dir.Path());
  Reconstruction read;
  read.ReadBinary(dir.Path());
  ExpectModelsEqual(model, read);

  // Read() prefers the binary files when both formats are present.
  Reconstruction other = MakeModel();
  other.images.erase(9);
  other.WriteText(dir.Path());
  Reconstruction read_auto;
  read_auto.Read(dir.Path());
  EXPECT_EQ(read_auto.images.size(), 3u);
}

TEST(Reconstruction, BinaryLayoutMatchesColmap) {
  TemporaryDirectory dir;
  Reconstruction model;
  ModelCamera camera;
  camera.camera_id = 3;
  camera.model_id = 0;
  camera.width = 10;
  camera.height = 20;
  camera.params = {1, 2, 3};
  model.cameras[3] = camera;
  ModelImage image;
  image.image_id = 4;
  image.camera_id = 3;
  image.name = "ab";
  image.points2D = {Eigen::Vector2d(1, 2)};
  image.point3D_ids = {kInvalidPoint3DId};
  model.images[4] = image;
  test::WriteBinaryModel(model, dir.Path());
  // u64 n + (u32 id, i32 model, u64 w, u64 h, 3 f64).
  EXPECT_EQ(ReadTextFile(JoinPaths(dir.Path(), "cameras.bin")).size(),
            8u + 4 + 4 + 8 + 8 + 3 * 8);
  // u64 n + (u32 id, 7 f64, u32 camera, "ab\0", u64 n2d, (2 f64, u64)).
  const std::string images = ReadTextFile(JoinPaths(dir.Path(), "images.bin"));
  EXPECT_EQ(images.size(), 8u + 4 + 56 + 4 + 3 + 8 + 24);
  EXPECT_EQ(images.substr(8 + 4 + 56 + 4, 3), std::string("ab\0", 3));
  // The missing point3D id is written as -1.
  EXPECT_EQ(images.substr(images.size() - 8), std::string(8, '\xff'));
  EXPECT_EQ(ReadTextFile(JoinPaths(dir.Path(), "points3D.bin")),
            std::string(8, '\0'));
}

TEST(Reconstruction, ReadsHandWrittenText) {
  TemporaryDirectory dir;
  WriteFileAtomically(JoinPaths(dir.Path(), "cameras.txt"),
                      "# CAMERA_ID MODEL WIDTH HEIGHT PARAMS[]\n"
                      "\n"
                      "1 SIMPLE_RADIAL 640 480 500 320 240 0.01\n");
  WriteFileAtomically(JoinPaths(dir.Path(), "images.txt"),
                      "# IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME\n"
                      "# POINTS2D[] as (X, Y, POINT3D_ID)\n"
                      "3 1 0 0 0 0.5 0 0 1 b.jpg\n"
                      "\n"
                      "1 1 0 0 0 0 0 0 1 a.jpg\n"
                      "10.5 20 -1 30 40 7\n");
  // No points3D.txt: read as empty (documented).
  Reconstruction model;
  model.Read(dir.Path());
  ASSERT_EQ(model.images.size(), 2u);
  EXPECT_TRUE(model.images.at(3).points2D.empty());
  EXPECT_EQ(model.images.at(3).tvec.x(), 0.5);
  const ModelImage& image = model.images.at(1);
  EXPECT_EQ(image.name, "a.jpg");
  ASSERT_EQ(image.points2D.size(), 2u);
  EXPECT_EQ(image.points2D[0], Eigen::Vector2d(10.5, 20));
  EXPECT_EQ(image.point3D_ids[0], kInvalidPoint3DId);
  EXPECT_EQ(image.point3D_ids[1], 7u);
  EXPECT_TRUE(model.points3D.empty());

  WriteFileAtomically(JoinPaths(dir.Path(), "points3D.txt"),
                      "# header\n7 1 2 3 255 0 10 0.5 1 1\n");
  model.ReadText(dir.Path());
  ASSERT_EQ(model.points3D.size(), 1u);
  EXPECT_EQ(model.points3D.at(7).color(2), 10);
  EXPECT_EQ(model.points3D.at(7).track.size(), 1u);
}

TEST(Reconstruction, MalformedTextIsErrorNamingFile) {
  TemporaryDirectory dir;
  MakeModel().WriteText(dir.Path());
  const std::string cameras = JoinPaths(dir.Path(), "cameras.txt");
  const std::string images = JoinPaths(dir.Path(), "images.txt");
  const std::string points = JoinPaths(dir.Path(), "points3D.txt");
  Reconstruction model;

  WriteFileAtomically(cameras, "1 PINHOLE 640 480 1 2 3\n");  // 3 of 4 params
  ExpectErrorNaming([&] { model.ReadText(dir.Path()); }, cameras);
  WriteFileAtomically(cameras, "1 NOT_A_MODEL 640 480 1 2 3\n");
  ExpectErrorNaming([&] { model.ReadText(dir.Path()); }, cameras);
  WriteFileAtomically(cameras, "1 PINHOLE 640 480 1 2 3 x\n");
  ExpectErrorNaming([&] { model.ReadText(dir.Path()); }, cameras);
  WriteFileAtomically(cameras, "1 PINHOLE 640 480 1 2 3 4\n");

  WriteFileAtomically(images, "1 1 0 0 0 0 0 0 1 a.jpg\n1 2 -1 3\n");
  ExpectErrorNaming([&] { model.ReadText(dir.Path()); }, images + ":2");
  // An image line missing its second line runs into the next image line.
  WriteFileAtomically(images,
                      "1 1 0 0 0 0 0 0 1 a.jpg\n2 1 0 0 0 0 0 0 1 b.jpg\n");
  ExpectErrorNaming([&] { model.ReadText(dir.Path()); }, images);
  WriteFileAtomically(images, "1 1 0 0 0 0 0 0 1\n\n");
  ExpectErrorNaming([&] { model.ReadText(dir.Path()); }, images);
  WriteFileAtomically(images, "1 1 0 0 0 0 0 0 1 a.jpg\n\n");

  WriteFileAtomically(points, "1 0 0 0 256 0 0 1\n");  // colour out of range
  ExpectErrorNaming([&] { model.ReadText(dir.Path()); }, points);
  WriteFileAtomically(points, "1 0 0 0 1 2 3 0.5 1\n");  // odd track
  ExpectErrorNaming([&] { model.ReadText(dir.Path()); }, points);

  // A failed read leaves the previous contents alone.
  Reconstruction kept = MakeModel();
  EXPECT_THROW(kept.ReadText(dir.Path()), Error);
  EXPECT_EQ(kept.images.size(), 3u);

  TemporaryDirectory empty;
  ExpectErrorNaming([&] { model.Read(empty.Path()); }, empty.Path());
  ExpectErrorNaming([&] { model.ReadText(empty.Path()); },
                    JoinPaths(empty.Path(), "cameras.txt"));
  ExpectErrorNaming([&] { model.ReadBinary(empty.Path()); },
                    JoinPaths(empty.Path(), "cameras.bin"));
}

// Found by fuzzing: fields separated by a vertical tab (white space to the
// field splitter, not to the name search) made the name search run past the
// line end and std::string::substr throw std::out_of_range; a number with an
// embedded NUL byte parsed as its prefix.
TEST(Reconstruction, TextOddWhiteSpaceAndNulBytesAreHandled) {
  TemporaryDirectory dir;
  const std::string cameras = JoinPaths(dir.Path(), "cameras.txt");
  const std::string images = JoinPaths(dir.Path(), "images.txt");
  WriteFileAtomically(cameras, "1 PINHOLE 640 480 1 2 3 4\n");
  Reconstruction model;
  WriteFileAtomically(images,
                      "3 0.95\v0 0 3 -1 0.5 2 1\va.jpg\n\n"
                      "4 1 0 0 0 0 0 0 1\vb c.jpg\n\n");
  model.ReadText(dir.Path());
  ASSERT_EQ(model.images.size(), 2u);
  EXPECT_EQ(model.images.at(3).name, "a.jpg");
  EXPECT_EQ(model.images.at(4).name, "b c.jpg");
  WriteFileAtomically(images,
                      std::string("3 1 0 0 0 0 0 0 1 a.jpg\n1 2\0x -1\n", 33));
  ExpectErrorNaming([&] { model.ReadText(dir.Path()); }, images + ":2");
  WriteFileAtomically(cameras,
                      std::string("1 PINHOLE 640 480\0 1 2 3 4\n", 27));
  ExpectErrorNaming([&] { model.ReadText(dir.Path()); }, cameras + ":1");
}

TEST(Reconstruction, TruncatedBinaryIsErrorNamingFile) {
  TemporaryDirectory dir;
  test::WriteBinaryModel(MakeModel(), dir.Path());
  for (const char* name : {"cameras.bin", "images.bin", "points3D.bin"}) {
    const std::string path = JoinPaths(dir.Path(), name);
    const std::string original = ReadTextFile(path);
    for (const size_t size : {size_t{0},
                              size_t{5},
                              size_t{8},
                              size_t{20},
                              original.size() / 2,
                              original.size() - 1}) {
      WriteFileAtomically(path, original.substr(0, size));
      Reconstruction model;
      ExpectErrorNaming([&] { model.ReadBinary(dir.Path()); }, path);
    }
    WriteFileAtomically(path, original + "x");  // trailing garbage
    Reconstruction model;
    ExpectErrorNaming([&] { model.ReadBinary(dir.Path()); }, path);
    // A huge count must fail cleanly, not allocate.
    std::string huge = original;
    huge.replace(0, 8, std::string(8, '\x7f'));
    WriteFileAtomically(path, huge);
    ExpectErrorNaming([&] { model.ReadBinary(dir.Path()); }, path);
    WriteFileAtomically(path, original);
  }
  Reconstruction model;
  model.ReadBinary(dir.Path());
  ExpectModelsEqual(MakeModel(), model);
}

TEST(Reconstruction, WriterRejectsInconsistentModels) {
  TemporaryDirectory dir;
  Reconstruction model = MakeModel();
  model.cameras[1].params.pop_back();
  EXPECT_THROW(model.WriteText(dir.Path()), Error);
  model = MakeModel();
  model.images[2].point3D_ids.pop_back();
  EXPECT_THROW(model.WriteText(dir.Path()), Error);
}

// The real COLMAP must accept what we write and we must read what it writes.
TEST(Reconstruction, RealColmapConvertsAndAnalyzesOurModels) {
  const std::string colmap = test::RealColmapExe();
  if (colmap.empty()) {
    GTEST_SKIP() << "the real colmap binary is not installed";
  }
  TemporaryDirectory dir;
  const Reconstruction model = MakeModel();
  const std::string text_dir = JoinPaths(dir.Path(), "text");
  const std::string bin_dir = JoinPaths(dir.Path(), "bin");
  const std::string text_again_dir = JoinPaths(dir.Path(), "text_again");
  const std::string ours_bin_dir = JoinPaths(dir.Path(), "ours_bin");
  model.WriteText(text_dir);
  test::WriteBinaryModel(model, ours_bin_dir);
  CreateDirIfNotExists(bin_dir);
  CreateDirIfNotExists(text_again_dir);

  std::string output;
  ASSERT_EQ(
      test::RunShell(ShellQuote(colmap) + " model_converter --input_path " +
                         ShellQuote(text_dir) + " --output_path " +
                         ShellQuote(bin_dir) + " --output_type BIN",
                     &output),
      0)
      << output;
  Reconstruction converted;
  converted.ReadBinary(bin_dir);
  ExpectModelsEqual(model, converted);
  // Same layout as our own binary writer (COLMAP orders records by its hash
  // maps, so only the sizes can be compared byte-wise).
  for (const char* name : {"cameras.bin", "images.bin", "points3D.bin"}) {
    EXPECT_EQ(ReadTextFile(JoinPaths(bin_dir, name)).size(),
              ReadTextFile(JoinPaths(ours_bin_dir, name)).size())
        << name;
  }

  ASSERT_EQ(
      test::RunShell(ShellQuote(colmap) + " model_converter --input_path " +
                         ShellQuote(ours_bin_dir) + " --output_path " +
                         ShellQuote(text_again_dir) + " --output_type TXT",
                     &output),
      0)
      << output;
  Reconstruction text_again;
  text_again.ReadText(text_again_dir);
  ExpectModelsEqual(model, text_again);

  ASSERT_EQ(test::RunShell(ShellQuote(colmap) + " model_analyzer --path " +
                               ShellQuote(text_dir),
                           &output),
            0)
      << output;
  EXPECT_NE(output.find("Cameras: 2"), std::string::npos) << output;
  EXPECT_NE(output.find("Images: 3"), std::string::npos) << output;
  EXPECT_NE(output.find("Points: 4"), std::string::npos) << output;
  EXPECT_NE(output.find("Observations: 12"), std::string::npos) << output;
}

TEST(Reconstruction, ReadsSharedFountainGroundTruth) {
  const std::string datasets = test::SharedDatasetsDir();
  const std::string gt = JoinPaths(datasets, "fountain-P11/gt");
  if (datasets.empty() || !ExistsDir(gt)) {
    GTEST_SKIP() << "shared datasets not available";
  }
  Reconstruction model;
  model.Read(gt);
  EXPECT_EQ(model.images.size(), 11u);
  ASSERT_FALSE(model.cameras.empty());
  for (const auto& [camera_id, camera] : model.cameras) {
    EXPECT_EQ(CameraModelIdToName(camera.model_id), "PINHOLE");
    EXPECT_EQ(camera.params.size(), 4u);
  }
  for (const auto& [image_id, image] : model.images) {
    EXPECT_EQ(model.cameras.count(image.camera_id), 1u);
    EXPECT_NEAR(image.qvec.norm(), 1.0, 1e-6);
  }
  EXPECT_NE(model.FindImageWithName("0000.jpg"), kInvalidImageId);
}

}  // namespace
}  // namespace colmap_gcn
