#include "scene/database.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "scene/colmap_scene_fixture.h"
#include "scene/database_inspector.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using test::DatabaseInspector;
using test::ExecuteSql;
using test::ExpectErrorContaining;
using test::FeatureKeypoints;
using test::FeatureMatches;
using test::kColmap38Schema;
using test::QuerySqlInt;
using test::TwoViewGeometry;

// A COLMAP 4.x-like layout: rigs/frames/frame_data/pose_priors tables, images
// without prior columns, descriptors with a type column.
const char* const kColmap4Schema = R"sql(
CREATE TABLE rigs (rig_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  ref_sensor_id INTEGER NOT NULL, ref_sensor_type INTEGER NOT NULL);
CREATE TABLE rig_sensors (rig_id INTEGER NOT NULL, sensor_id INTEGER NOT NULL,
  sensor_type INTEGER NOT NULL, sensor_from_rig BLOB);
CREATE TABLE cameras (camera_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  model INTEGER NOT NULL, width INTEGER NOT NULL, height INTEGER NOT NULL,
  params BLOB, prior_focal_length INTEGER NOT NULL);
CREATE TABLE frames (frame_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  rig_id INTEGER NOT NULL);
CREATE TABLE frame_data (frame_id INTEGER NOT NULL, data_id INTEGER NOT NULL,
  sensor_id INTEGER NOT NULL, sensor_type INTEGER NOT NULL);
CREATE TABLE images (image_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  name TEXT NOT NULL UNIQUE, camera_id INTEGER NOT NULL);
CREATE TABLE pose_priors (image_id INTEGER PRIMARY KEY NOT NULL,
  position BLOB, coordinate_system INTEGER NOT NULL, position_covariance BLOB);
CREATE TABLE keypoints (image_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB);
CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB,
  type INTEGER NOT NULL DEFAULT 0);
CREATE TABLE matches (pair_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB);
CREATE TABLE two_view_geometries (pair_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB,
  config INTEGER NOT NULL, F BLOB, E BLOB, H BLOB, qvec BLOB, tvec BLOB);
)sql";

// Hex literal of raw little-endian bytes for SQL (X'..').
template <typename T>
std::string HexBlob(const std::vector<T>& values) {
  static const char* const kDigits = "0123456789ABCDEF";
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  std::string hex = "X'";
  for (size_t i = 0; i < values.size() * sizeof(T); ++i) {
    hex += kDigits[bytes[i] >> 4];
    hex += kDigits[bytes[i] & 15];
  }
  return hex + "'";
}

std::string ReadFileBytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), {});
}

TEST(PairId, EncodesSmallerIdFirst) {
  EXPECT_EQ(ImagePairToPairId(1, 2), kMaxNumImages * 1 + 2);
  EXPECT_EQ(ImagePairToPairId(2, 1), kMaxNumImages * 1 + 2);
  EXPECT_EQ(ImagePairToPairId(0, 5), 5u);
  EXPECT_EQ(PairIdToImagePair(kMaxNumImages * 3 + 7), ImagePair(3, 7));
  EXPECT_TRUE(SwapImagePair(2, 1));
  EXPECT_FALSE(SwapImagePair(1, 2));
  EXPECT_FALSE(SwapImagePair(4, 4));
}

TEST(PairId, LargeIdsRoundTrip) {
  const image_t big = static_cast<image_t>(kMaxNumImages - 1);
  const image_pair_t pair_id = ImagePairToPairId(big, big - 1);
  EXPECT_EQ(pair_id, kMaxNumImages * (big - 1) + big);
  // Must stay within sqlite's signed 64-bit integers.
  EXPECT_LE(pair_id, static_cast<image_pair_t>(INT64_MAX));
  EXPECT_EQ(PairIdToImagePair(pair_id), ImagePair(big - 1, big));
  EXPECT_THROW(ImagePairToPairId(static_cast<image_t>(kMaxNumImages), 1),
               Error);

  std::mt19937 rng(42);
  std::uniform_int_distribution<image_t> id(0, big);
  for (int i = 0; i < 10000; ++i) {
    const image_t a = id(rng);
    const image_t b = id(rng);
    const ImagePair pair = PairIdToImagePair(ImagePairToPairId(a, b));
    EXPECT_EQ(pair.first, std::min(a, b));
    EXPECT_EQ(pair.second, std::max(a, b));
    EXPECT_EQ(ImagePairToPairId(a, b), ImagePairToPairId(b, a));
  }
}

TEST(TwoViewGeometryConfig, VerifiedConfigs) {
  for (int config = 0; config <= 9; ++config) {
    const bool verified_config = config == 2 || config == 3 || config == 4 ||
                                 config == 5 || config == 6 || config == 8;
    EXPECT_EQ(IsVerifiedTwoViewGeometry(config, 15, 15), verified_config)
        << config;
    EXPECT_FALSE(IsVerifiedTwoViewGeometry(config, 14, 15)) << config;
  }
}

TEST(Database, MissingFileIsErrorAndNotCreated) {
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "missing.db");
  ExpectErrorContaining([&] { Database database(path); },
                        "database not found: " + path);
  ExpectErrorContaining(
      [&] { Database database(path, Database::Mode::kReadWrite); },
      "database not found");
  EXPECT_FALSE(ExistsFile(path));
  ExpectErrorContaining([&] { Database database(dir.Path()); },
                        "database not found");
}

TEST(Database, NonSqliteFileIsError) {
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "random.db");
  std::mt19937 rng(3);
  std::string bytes(8192, '\0');
  for (char& byte : bytes) byte = static_cast<char>(rng());
  WriteFileAtomically(path, bytes);
  ExpectErrorContaining([&] { Database database(path); },
                        "not a COLMAP database");
  ExpectErrorContaining([&] { Database database(path); }, path);
  EXPECT_EQ(ReadFileBytes(path), bytes);
}

TEST(Database, EmptyAndForeignSqliteDatabasesAreErrors) {
  TemporaryDirectory dir;
  const std::string empty_path = JoinPaths(dir.Path(), "empty.db");
  WriteFileAtomically(empty_path, "");  // a valid, empty SQLite database
  ExpectErrorContaining([&] { Database database(empty_path); },
                        "not a COLMAP database");

  const std::string other_path = JoinPaths(dir.Path(), "other.db");
  ExecuteSql(other_path, "CREATE TABLE people (name TEXT);");
  ExpectErrorContaining([&] { Database database(other_path); },
                        "not a COLMAP database");

  // Some COLMAP tables but not all of them.
  const std::string partial_path = JoinPaths(dir.Path(), "partial.db");
  ExecuteSql(partial_path,
             "CREATE TABLE cameras (camera_id INTEGER);"
             "CREATE TABLE images (image_id INTEGER, name TEXT, "
             "camera_id INTEGER, prior_qw REAL);");
  ExpectErrorContaining([&] { Database database(partial_path); },
                        "missing tables: keypoints");
}

TEST(Database, DetectsSchemas) {
  TemporaryDirectory dir;
  const std::string old_path = JoinPaths(dir.Path(), "colmap38.db");
  ExecuteSql(old_path, kColmap38Schema);
  EXPECT_EQ(Database(old_path).Schema(), DatabaseSchema::kColmap38);

  const std::string new_path = JoinPaths(dir.Path(), "colmap4.db");
  ExecuteSql(new_path, kColmap4Schema);
  ExecuteSql(new_path,
             "INSERT INTO cameras VALUES (1, 1, 640, 480, " +
                 HexBlob(std::vector<double>{500, 501, 320, 240}) +
                 ", 0);"
                 "INSERT INTO images VALUES (1, 'a.jpg', 1);");
  DatabaseInspector database(new_path);
  EXPECT_EQ(database.Schema(), DatabaseSchema::kColmap39Plus);
  EXPECT_STREQ(DatabaseSchemaName(database.Schema()), "COLMAP 3.9+");
  EXPECT_EQ(database.NumImages(), 1u);
  EXPECT_EQ(database.ReadImageWithName("a.jpg").camera_id, 1u);
  ASSERT_EQ(database.ReadAllCameras().size(), 1u);
  EXPECT_EQ(database.ReadAllCameras()[0].params,
            (std::vector<double>{500, 501, 320, 240}));

  // A 3.9/3.10-style database: images keeps no priors, pose_priors exists.
  const std::string mid_path = JoinPaths(dir.Path(), "colmap310.db");
  ExecuteSql(mid_path, kColmap38Schema);
  ExecuteSql(mid_path,
             "CREATE TABLE pose_priors (image_id INTEGER PRIMARY KEY, "
             "position BLOB, coordinate_system INTEGER);");
  EXPECT_EQ(Database(mid_path).Schema(), DatabaseSchema::kColmap39Plus);

  // Neither 3.8 priors nor newer tables: unknown.
  const std::string odd_path = JoinPaths(dir.Path(), "odd.db");
  ExecuteSql(odd_path, kColmap4Schema);
  ExecuteSql(odd_path,
             "DROP TABLE rigs; DROP TABLE rig_sensors; DROP TABLE frames;"
             "DROP TABLE frame_data; DROP TABLE pose_priors;");
  ExpectErrorContaining([&] { Database database(odd_path); },
                        "unrecognised COLMAP database schema");
}

// A hand-written 3.8 database with known blobs between images 3 and 5.
class HandMadeDatabase : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = JoinPaths(dir_.Path(), "database.db");
    ExecuteSql(path_, kColmap38Schema);
    const image_pair_t pair_id = ImagePairToPairId(3, 5);
    // F/E/H are stored row-major; H is invertible, qvec a 90 degree turn.
    F_ << 1, 2, 3, 4, 5, 6, 7, 8, 10;
    H_ << 2, 0, 5, 0, 3, 1, 0.001, 0, 1;
    qvec_ = Eigen::Vector4d(std::sqrt(0.5), 0, 0, std::sqrt(0.5));
    tvec_ = Eigen::Vector3d(1, 2, 3);
    const auto row_major = [](const Eigen::Matrix3d& m) {
      std::vector<double> values;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) values.push_back(m(r, c));
      return values;
    };
    ExecuteSql(
        path_,
        "INSERT INTO cameras VALUES (1, 0, 100, 80, " +
            HexBlob(std::vector<double>{90, 50, 40}) +
            ", 1);"
            "INSERT INTO images (image_id, name, camera_id) VALUES "
            "(5, 'b.png', 1), (3, 'c.png', 1), (9, 'a.png', 1);"
            "INSERT INTO keypoints VALUES (3, 2, 4, " +
            HexBlob(std::vector<float>{1, 2, 3, 4, 5, 6, 7, 8}) +
            "), (5, 0, 4, NULL);"
            "INSERT INTO descriptors VALUES (3, 1, 128, " +
            HexBlob(std::vector<uint8_t>(128, 7)) +
            ");"
            "INSERT INTO matches VALUES (" +
            std::to_string(pair_id) + ", 3, 2, " +
            HexBlob(std::vector<uint32_t>{0, 10, 1, 11, 2, 12}) +
            ");"
            "INSERT INTO two_view_geometries VALUES (" +
            std::to_string(pair_id) + ", 2, 2, " +
            HexBlob(std::vector<uint32_t>{0, 10, 2, 12}) + ", 2, " +
            HexBlob(row_major(F_)) + ", " + HexBlob(row_major(2 * F_)) + ", " +
            HexBlob(row_major(H_)) + ", " +
            HexBlob(std::vector<double>(qvec_.data(), qvec_.data() + 4)) +
            ", " +
            HexBlob(std::vector<double>(tvec_.data(), tvec_.data() + 3)) +
            ");"
            "INSERT INTO two_view_geometries VALUES (" +
            std::to_string(ImagePairToPairId(3, 9)) +
            ", 0, 0, NULL, 0, NULL, NULL, NULL, NULL, NULL);");
  }

  TemporaryDirectory dir_;
  std::string path_;
  Eigen::Matrix3d F_;
  Eigen::Matrix3d H_;
  Eigen::Vector4d qvec_;
  Eigen::Vector3d tvec_;
};

TEST_F(HandMadeDatabase, ReadsCountsImagesAndFeatures) {
  DatabaseInspector database(path_);
  EXPECT_EQ(database.Schema(), DatabaseSchema::kColmap38);
  EXPECT_EQ(database.NumCameras(), 1u);
  EXPECT_EQ(database.NumImages(), 3u);
  EXPECT_EQ(database.NumKeypoints(), 2u);
  EXPECT_EQ(database.NumDescriptors(), 1u);
  EXPECT_EQ(database.NumMatchedPairs(), 1u);
  EXPECT_EQ(database.NumTwoViewGeometries(), 2u);

  const std::vector<DatabaseCamera> cameras = database.ReadAllCameras();
  ASSERT_EQ(cameras.size(), 1u);
  EXPECT_EQ(cameras[0].model_id, 0);
  EXPECT_EQ(cameras[0].width, 100u);
  EXPECT_EQ(cameras[0].height, 80u);
  EXPECT_TRUE(cameras[0].has_prior_focal_length);
  EXPECT_EQ(cameras[0].params, (std::vector<double>{90, 50, 40}));

  const std::vector<DatabaseImage> images = database.ReadAllImages();
  ASSERT_EQ(images.size(), 3u);
  EXPECT_EQ(images[0].image_id, 3u);
  EXPECT_EQ(images[0].name, "c.png");
  EXPECT_EQ(images[1].name, "b.png");
  EXPECT_EQ(images[2].image_id, 9u);
  EXPECT_TRUE(database.ExistsImageWithName("a.png"));
  EXPECT_FALSE(database.ExistsImageWithName("zzz.png"));
  EXPECT_EQ(database.ReadImageWithName("b.png").image_id, 5u);
  ExpectErrorContaining([&] { database.ReadImageWithName("zzz.png"); },
                        "zzz.png");

  const FeatureKeypoints keypoints = database.ReadKeypoints(3);
  ASSERT_EQ(keypoints.rows(), 2);
  ASSERT_EQ(keypoints.cols(), 4);
  EXPECT_EQ(keypoints(1, 0), 5.0f);
  EXPECT_EQ(keypoints(0, 3), 4.0f);
  EXPECT_EQ(database.ReadKeypoints(5).rows(), 0);  // NULL blob
  EXPECT_EQ(database.ReadKeypoints(9).rows(), 0);  // no row
  EXPECT_EQ(database.NumKeypointsForImage(3), 2u);

  const FeatureDescriptors descriptors = database.ReadDescriptors(3);
  ASSERT_EQ(descriptors.rows(), 1);
  ASSERT_EQ(descriptors.cols(), 128);
  EXPECT_EQ(descriptors(0, 127), 7);
  EXPECT_EQ(database.NumDescriptorsForImage(3), 1u);
  EXPECT_EQ(database.NumDescriptorsForImage(5), 0u);
}

TEST_F(HandMadeDatabase, OrientsMatchesAndGeometryAsRequested) {
  DatabaseInspector database(path_);
  const FeatureMatches forward = database.ReadMatches(3, 5);
  ASSERT_EQ(forward.rows(), 3);
  EXPECT_EQ(forward(2, 0), 2u);
  EXPECT_EQ(forward(2, 1), 12u);
  const FeatureMatches backward = database.ReadMatches(5, 3);
  ASSERT_EQ(backward.rows(), 3);
  EXPECT_EQ(backward(2, 0), 12u);
  EXPECT_EQ(backward(2, 1), 2u);
  EXPECT_TRUE(database.ExistsMatches(5, 3));
  EXPECT_FALSE(database.ExistsMatches(3, 9));
  EXPECT_EQ(database.ReadMatches(3, 9).rows(), 0);
  EXPECT_EQ(database.ReadMatchedPairIds(),
            std::vector<image_pair_t>{ImagePairToPairId(3, 5)});

  const TwoViewGeometry geometry = database.ReadTwoViewGeometry(3, 5);
  EXPECT_EQ(geometry.config, 2);
  ASSERT_EQ(geometry.inlier_matches.rows(), 2);
  EXPECT_EQ(geometry.inlier_matches(1, 1), 12u);
  EXPECT_EQ(geometry.F, F_);
  EXPECT_EQ(geometry.E, 2 * F_);
  EXPECT_EQ(geometry.H, H_);
  EXPECT_EQ(geometry.qvec, qvec_);
  EXPECT_EQ(geometry.tvec, tvec_);

  // The reverse direction is the inverse geometry, as in COLMAP.
  const TwoViewGeometry inverse = database.ReadTwoViewGeometry(5, 3);
  EXPECT_EQ(inverse.config, 2);
  EXPECT_EQ(inverse.inlier_matches(1, 0), 12u);
  EXPECT_EQ(inverse.inlier_matches(1, 1), 2u);
  EXPECT_EQ(inverse.F, F_.transpose());
  EXPECT_TRUE(inverse.H.isApprox(H_.inverse()));
  const Eigen::Quaterniond q(qvec_(0), qvec_(1), qvec_(2), qvec_(3));
  const Eigen::Quaterniond q_inv(
      inverse.qvec(0), inverse.qvec(1), inverse.qvec(2), inverse.qvec(3));
  EXPECT_TRUE(
      (q * q_inv).toRotationMatrix().isApprox(Eigen::Matrix3d::Identity()));
  // x2 = R x1 + t  <=>  x1 = R' x2 + t'.
  const Eigen::Vector3d x1(0.3, -1.0, 4.0);
  const Eigen::Vector3d x2 = q * x1 + tvec_;
  EXPECT_TRUE((q_inv * x2 + inverse.tvec).isApprox(x1));

  // A failed pair with NULL blobs.
  const TwoViewGeometry failed = database.ReadTwoViewGeometry(9, 3);
  EXPECT_EQ(failed.config, 0);
  EXPECT_EQ(failed.inlier_matches.rows(), 0);
  EXPECT_EQ(failed.F, Eigen::Matrix3d::Zero());
  EXPECT_TRUE(database.ExistsTwoViewGeometry(9, 3));
  EXPECT_FALSE(database.ExistsTwoViewGeometry(9, 5));

  const std::vector<TwoViewGeometryInfo> infos =
      database.ReadTwoViewGeometryInfos();
  ASSERT_EQ(infos.size(), 2u);
  EXPECT_EQ(infos[0].pair_id, ImagePairToPairId(3, 5));
  EXPECT_EQ(infos[0].config, 2);
  EXPECT_EQ(infos[0].num_inliers, 2u);
  EXPECT_EQ(infos[1].config, 0);
  EXPECT_EQ(infos[1].num_inliers, 0u);
}

TEST_F(HandMadeDatabase, CorruptBlobIsError) {
  ExecuteSql(path_,
             "UPDATE keypoints SET rows = 3 WHERE image_id = 3;"
             "UPDATE matches SET cols = 3;"
             "UPDATE descriptors SET rows = 2 WHERE image_id = 3;");
  DatabaseInspector database(path_);
  ExpectErrorContaining([&] { database.ReadKeypoints(3); }, path_);
  ExpectErrorContaining([&] { database.ReadMatches(3, 5); }, "matches");
  ExpectErrorContaining([&] { database.ReadDescriptors(3); }, "descriptors");
}

TEST_F(HandMadeDatabase, ReadOnlyNeverWrites) {
  const std::string before = ReadFileBytes(path_);
  {
    DatabaseInspector database(path_);
    DatabaseCamera camera = database.ReadAllCameras()[0];
    EXPECT_THROW(database.UpdateCamera(camera), Error);
  }
  EXPECT_EQ(ReadFileBytes(path_), before);
}

TEST_F(HandMadeDatabase, WritesCamera) {
  {
    Database database(path_, Database::Mode::kReadWrite);
    DatabaseCamera camera;
    camera.camera_id = 1;
    camera.model_id = 1;  // PINHOLE
    camera.width = 1536;
    camera.height = 1024;
    camera.params = {1379.74, 1382.08, 760.095, 503.155};
    camera.has_prior_focal_length = true;
    database.UpdateCamera(camera);

    camera.params.pop_back();
    EXPECT_THROW(database.UpdateCamera(camera), Error);  // wrong count
    camera.params.push_back(1);
    camera.camera_id = 77;
    EXPECT_THROW(database.UpdateCamera(camera), Error);  // no such camera
  }
  DatabaseInspector database(path_);
  const DatabaseCamera camera = database.ReadAllCameras()[0];
  EXPECT_EQ(camera.model_id, 1);
  EXPECT_EQ(camera.width, 1536u);
  EXPECT_EQ(camera.params,
            (std::vector<double>{1379.74, 1382.08, 760.095, 503.155}));
  EXPECT_EQ(database.NumKeypoints(), 2u);
}

}  // namespace
}  // namespace colmap_gcn
