#include "evaluation/bundler.h"
#include "evaluation/bundler_writer.h"

#include <gtest/gtest.h>

#include "scene/camera_models.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

// Three cameras (the second unregistered, f = 0), two points. Camera 0 sits
// at (0, 0, 10) looking down -z at the origin (Bundler: R = I, t = -R C);
// camera 2 at (10, 0, 0) looking down -x. Point (1, 2, 0) projects in
// camera 0 to p = -P / P_z = (0.1, 0.2), i.e. (50, 100) for f = 500 (y up).
const char* kBundle =
    "# Bundle file v0.3\n"
    "3 2\n"
    "500 0.01 -0.002\n"
    "1 0 0\n0 1 0\n0 0 1\n"
    "0 0 -10\n"
    "0 0 0\n"
    "1 0 0\n0 1 0\n0 0 1\n"
    "0 0 0\n"
    "400 0 0\n"
    "0 0 -1\n0 1 0\n1 0 0\n"
    "0 0 -10\n"
    "1 2 0\n"
    "255 128 0\n"
    "2 0 7 50 100 2 3 -20 200\n"
    "0 0 0\n"
    "10 20 30\n"
    "1 1 4 0 0\n";

TEST(Bundler, ParsesHandWrittenFile) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "bundle.out");
  WriteFileAtomically(path, kBundle);
  const BundlerFile bundle = ReadBundlerFile(path);
  ASSERT_EQ(bundle.cameras.size(), 3u);
  ASSERT_EQ(bundle.points.size(), 2u);
  EXPECT_DOUBLE_EQ(bundle.cameras[0].focal_length, 500);
  EXPECT_DOUBLE_EQ(bundle.cameras[0].k1, 0.01);
  EXPECT_DOUBLE_EQ(bundle.cameras[0].k2, -0.002);
  EXPECT_FALSE(bundle.cameras[1].IsRegistered());
  EXPECT_DOUBLE_EQ(bundle.cameras[2].rotation(0, 2), -1);
  EXPECT_DOUBLE_EQ(bundle.cameras[2].translation(2), -10);
  EXPECT_EQ(bundle.points[0].views.size(), 2u);
  EXPECT_EQ(bundle.points[0].views[1].camera_idx, 2);
  EXPECT_EQ(bundle.points[0].views[0].key_idx, 7);
  EXPECT_DOUBLE_EQ(bundle.points[0].views[1].y, 200);
  EXPECT_EQ(bundle.points[0].color, Eigen::Vector3i(255, 128, 0));

  const Reconstruction model = BundlerToReconstruction(
      bundle, {"a.jpg", "b.jpg", "c.jpg"}, {{640, 480}, {0, 0}, {800, 600}});
  ASSERT_EQ(model.images.size(), 2u);  // b.jpg (f = 0) left out
  EXPECT_EQ(model.FindImageWithName("b.jpg"), kInvalidImageId);
  const ModelImage& a = model.images.at(model.FindImageWithName("a.jpg"));
  const ModelCamera& camera_a = model.cameras.at(a.camera_id);
  EXPECT_EQ(CameraModelIdToName(camera_a.model_id), "RADIAL");
  EXPECT_EQ(camera_a.params,
            (std::vector<double>{500, 320, 240, 0.01, -0.002}));
  // R_colmap = diag(1,-1,-1) R, the centre is unchanged.
  EXPECT_LT((a.RotationMatrix() -
             Eigen::Matrix3d(Eigen::Vector3d(1, -1, -1).asDiagonal()))
                .norm(),
            1e-12);
  EXPECT_LT((a.ProjectionCenter() - Eigen::Vector3d(0, 0, 10)).norm(), 1e-12);
  const ModelImage& c = model.images.at(model.FindImageWithName("c.jpg"));
  EXPECT_LT((c.ProjectionCenter() - Eigen::Vector3d(10, 0, 0)).norm(), 1e-12);

  // The observation is where COLMAP's pinhole projection puts the point.
  const Eigen::Vector3d in_camera =
      a.RotationMatrix() * Eigen::Vector3d(1, 2, 0) + a.tvec;
  ASSERT_GT(in_camera.z(), 0);  // in front of the camera
  const Eigen::Vector2d projected(500 * in_camera.x() / in_camera.z() + 320,
                                  500 * in_camera.y() / in_camera.z() + 240);
  ASSERT_EQ(a.points2D.size(), 1u);
  EXPECT_LT((a.points2D[0] - projected).norm(), 1e-9);
  EXPECT_LT((a.points2D[0] - Eigen::Vector2d(370, 140)).norm(), 1e-9);
  // Point 1 is seen only by the unregistered camera: dropped.
  EXPECT_EQ(model.points3D.size(), 1u);
  EXPECT_EQ(model.points3D.begin()->second.track.size(), 2u);

  // Writing back and reading gives the same cameras and observations.
  const std::string out = JoinPaths(dir.Path(), "again.out");
  test::WriteBundlerFile(
      out, ReconstructionToBundler(model, {"a.jpg", "b.jpg", "c.jpg"}));
  const BundlerFile again = ReadBundlerFile(out);
  ASSERT_EQ(again.cameras.size(), 3u);
  EXPECT_FALSE(again.cameras[1].IsRegistered());
  EXPECT_LT((again.cameras[2].rotation - bundle.cameras[2].rotation).norm(),
            1e-12);
  EXPECT_DOUBLE_EQ(again.cameras[0].k2, -0.002);
  ASSERT_EQ(again.points.size(), 1u);
  EXPECT_DOUBLE_EQ(again.points[0].views[1].x, -20);
  EXPECT_DOUBLE_EQ(again.points[0].views[1].y, 200);
}

TEST(Bundler, MalformedFilesAreErrorsNamingTheFile) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "bad.out");
  WriteFileAtomically(path, "# Bundle file v0.3\n1 0\n500 0 0\n1 0 0\n");
  try {
    ReadBundlerFile(path);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("bad.out"), std::string::npos);
  }
  WriteFileAtomically(path,
                      "1 1\n500 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n"
                      "0 0 0\n1 1 1\n2 0 0 1 1\n");
  EXPECT_THROW(ReadBundlerFile(path), Error);  // view list too short
  WriteFileAtomically(path,
                      "1 1\n500 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n"
                      "0 0 0\n1 1 1\n1 5 0 1 1\n");
  EXPECT_THROW(ReadBundlerFile(path), Error);  // camera out of range
  EXPECT_THROW(ReadBundlerFile(JoinPaths(dir.Path(), "missing.out")), Error);
}

// Inputs the fuzzer found or that follow from them: counts and indices were
// cast from double unchecked (a count of 9e12 allocated 1.3 TB; NaN or 1e300
// is undefined behaviour), and a field with a NUL byte parsed as its prefix.
TEST(Bundler, CorruptCountsIndicesAndColoursAreErrorsNamingTheFile) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "bad.out");
  const std::string camera = "500 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n";
  const std::string cases[] = {
      "9223372036854 0\n",
      "nan 0\n",
      "1.5 0\n",
      "0 -1\n",
      "0 1\n0 0 0\n1e300 0 0\n0\n",
      "0 1\n0 0 0\n256 0 0\n0\n",
      "1 1\n" + camera + "0 0 0\n1 1 1\n1 1e300 0 1 1\n",
      "1 1\n" + camera + "0 0 0\n1 1 1\n1 0 -5 1 1\n",
      "1 1\n" + camera + "0 0 0\n1 1 1\n1e300\n",
      "1 1\n" + camera + "0 0 0\n1 1 1\n1.25 0 0 1 1\n",
      std::string("0 0\0junk\n", 9),
  };
  for (const std::string& contents : cases) {
    WriteFileAtomically(path, contents);
    try {
      ReadBundlerFile(path);
      ADD_FAILURE() << "no error for \"" << contents << "\"";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("bad.out"), std::string::npos)
          << error.what();
    }
  }
  WriteFileAtomically(path,
                      "1 1\n" + camera + "0 0 0\n255 0 7\n1 0 3 1.5 -2\n");
  const BundlerFile bundle = ReadBundlerFile(path);
  ASSERT_EQ(bundle.points.size(), 1u);
  EXPECT_EQ(bundle.points[0].color(0), 255);
  EXPECT_EQ(bundle.points[0].views[0].key_idx, 3);
}

}  // namespace
}  // namespace colmap_gcn
