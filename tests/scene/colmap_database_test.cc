// Reads a database written by the real COLMAP and checks every read against
// direct SQL on the same file.
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "scene/colmap_scene_fixture.h"
#include "scene/database.h"
#include "scene/database_inspector.h"
#include "scene/database_validation.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using test::DatabaseInspector;
using test::FeatureKeypoints;
using test::FeatureMatches;
using test::QuerySqlInt;
using test::TwoViewGeometry;

class ColmapDatabase : public ::testing::Test {
 protected:
  // COLMAP runs once for all tests of this suite (a few seconds on CPU).
  static void SetUpTestSuite() {
    const std::string colmap = test::RealColmapExe();
    if (colmap.empty()) return;
    dir_ = new TemporaryDirectory("scene_colmap_db");
    const std::string image_dir = JoinPaths(dir_->Path(), "images");
    names_ = new std::vector<std::string>(
        test::WriteOverlappingTestImages(image_dir, 4));
    database_path_ = new std::string(JoinPaths(dir_->Path(), "database.db"));
    log_ = new std::string;
    ok_ = test::RunColmapFeaturesAndMatching(
        colmap, image_dir, *database_path_, log_);
  }

  static void TearDownTestSuite() {
    delete names_;
    delete database_path_;
    delete log_;
    delete dir_;
    names_ = nullptr;
    database_path_ = nullptr;
    log_ = nullptr;
    dir_ = nullptr;
  }

  void SetUp() override {
    if (dir_ == nullptr) {
      GTEST_SKIP() << "the real colmap binary is not installed";
    }
    ASSERT_TRUE(ok_) << *log_;
  }

  static const std::string& Path() { return *database_path_; }

  static TemporaryDirectory* dir_;
  static std::vector<std::string>* names_;
  static std::string* database_path_;
  static std::string* log_;
  static bool ok_;
};

TemporaryDirectory* ColmapDatabase::dir_ = nullptr;
std::vector<std::string>* ColmapDatabase::names_ = nullptr;
std::string* ColmapDatabase::database_path_ = nullptr;
std::string* ColmapDatabase::log_ = nullptr;
bool ColmapDatabase::ok_ = false;

// The message of ValidateDatabaseForColmap on path, "" when it passes.
std::string Problem(const std::string& path) {
  try {
    ValidateDatabaseForColmap(Database(path));
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

// What COLMAP itself wrote passes the checks made for it: no false alarms.
TEST_F(ColmapDatabase, PassesTheChecksForColmap) {
  EXPECT_EQ(Problem(Path()), "");
}

// Why the check is made: COLMAP 3.8 verifying a pair of an image whose
// camera was deleted aborts (std::out_of_range) instead of reporting it.
TEST_F(ColmapDatabase, ColmapAbortsOnAnImageOfADeletedCamera) {
  TemporaryDirectory dir("scene_colmap_db_broken");
  const std::string broken = JoinPaths(dir.Path(), "broken.db");
  std::filesystem::copy_file(Path(), broken);
  test::ExecuteSql(broken,
                   "DELETE FROM matches; DELETE FROM two_view_geometries;"
                   "UPDATE images SET camera_id = 7 WHERE image_id = 2;");
  EXPECT_NE(Problem(broken).find("refers to camera 7"), std::string::npos);
  std::string output;
  EXPECT_NE(test::RunShell(test::RealColmapExe() +
                               " exhaustive_matcher --SiftMatching.use_gpu 0 "
                               "--database_path " +
                               broken,
                           &output),
            0)
      << output;
  EXPECT_NE(output.find("out_of_range"), std::string::npos) << output;
}

TEST_F(ColmapDatabase, CountsMatchSql) {
  DatabaseInspector database(Path());
  EXPECT_EQ(database.Schema(), DatabaseSchema::kColmap38);
  EXPECT_EQ(database.NumImages(), 4u);
  EXPECT_EQ(database.NumImages(),
            QuerySqlInt(Path(), "SELECT COUNT(*) FROM images"));
  EXPECT_EQ(database.NumCameras(), 1u);  // single_camera
  EXPECT_EQ(database.NumKeypoints(),
            QuerySqlInt(Path(), "SELECT SUM(rows) FROM keypoints"));
  EXPECT_EQ(database.NumDescriptors(),
            QuerySqlInt(Path(), "SELECT SUM(rows) FROM descriptors"));
  EXPECT_GT(database.NumKeypoints(), 400u);
  EXPECT_EQ(database.NumMatchedPairs(),
            QuerySqlInt(Path(), "SELECT COUNT(*) FROM matches"));
  EXPECT_EQ(database.NumTwoViewGeometries(),
            QuerySqlInt(Path(), "SELECT COUNT(*) FROM two_view_geometries"));
  EXPECT_EQ(database.NumTwoViewGeometries(), 6u);  // all pairs of 4
}

TEST_F(ColmapDatabase, ImageIdsMapToNames) {
  DatabaseInspector database(Path());
  const std::vector<DatabaseImage> images = database.ReadAllImages();
  ASSERT_EQ(images.size(), names_->size());
  std::set<std::string> names;
  for (const DatabaseImage& image : images) {
    names.insert(image.name);
    EXPECT_EQ(database.ReadImageWithName(image.name).image_id, image.image_id);
    EXPECT_EQ(image.image_id,
              QuerySqlInt(Path(),
                          "SELECT image_id FROM images WHERE name = '" +
                              image.name + "'"));
    EXPECT_EQ(image.camera_id, database.ReadAllCameras()[0].camera_id);
  }
  EXPECT_EQ(names, std::set<std::string>(names_->begin(), names_->end()));

  const std::vector<DatabaseCamera> cameras = database.ReadAllCameras();
  EXPECT_EQ(cameras[0].width, 640u);
  EXPECT_EQ(cameras[0].height, 480u);
  // Default model SIMPLE_RADIAL: f, cx, cy, k.
  EXPECT_EQ(cameras[0].model_id, 2);
  EXPECT_EQ(cameras[0].params.size(), 4u);
}

TEST_F(ColmapDatabase, FeaturesMatchSql) {
  DatabaseInspector database(Path());
  for (const DatabaseImage& image : database.ReadAllImages()) {
    const std::string where =
        " WHERE image_id = " + std::to_string(image.image_id);
    const FeatureKeypoints keypoints = database.ReadKeypoints(image.image_id);
    EXPECT_EQ(keypoints.rows(),
              QuerySqlInt(Path(), "SELECT rows FROM keypoints" + where));
    EXPECT_EQ(keypoints.cols(),
              QuerySqlInt(Path(), "SELECT cols FROM keypoints" + where));
    EXPECT_EQ(keypoints.cols(), 6);  // COLMAP 3.8 stores affine shapes
    // Keypoints lie inside the image (pixel centres at +0.5).
    EXPECT_GE(keypoints.col(0).minCoeff(), 0.0f);
    EXPECT_LE(keypoints.col(0).maxCoeff(), 640.0f);
    EXPECT_LE(keypoints.col(1).maxCoeff(), 480.0f);

    const FeatureDescriptors descriptors =
        database.ReadDescriptors(image.image_id);
    EXPECT_EQ(descriptors.rows(), keypoints.rows());
    EXPECT_EQ(descriptors.cols(), 128);
    EXPECT_EQ(QuerySqlInt(Path(), "SELECT cols FROM descriptors" + where), 128);
    EXPECT_EQ(database.NumDescriptorsForImage(image.image_id),
              static_cast<size_t>(descriptors.rows()));
  }
}

TEST_F(ColmapDatabase, MatchesAndGeometriesMatchSql) {
  DatabaseInspector database(Path());
  const std::vector<DatabaseImage> images = database.ReadAllImages();
  size_t num_verified = 0;
  for (const TwoViewGeometryInfo& info : database.ReadTwoViewGeometryInfos()) {
    const std::string where =
        " WHERE pair_id = " + std::to_string(info.pair_id);
    EXPECT_EQ(
        info.config,
        QuerySqlInt(Path(), "SELECT config FROM two_view_geometries" + where));
    EXPECT_EQ(
        info.num_inliers,
        QuerySqlInt(Path(), "SELECT rows FROM two_view_geometries" + where));
    num_verified += IsVerifiedTwoViewGeometry(info.config, info.num_inliers);

    const auto [id1, id2] = PairIdToImagePair(info.pair_id);
    ASSERT_LT(id1, id2);
    const TwoViewGeometry geometry = database.ReadTwoViewGeometry(id1, id2);
    EXPECT_EQ(geometry.config, info.config);
    EXPECT_EQ(static_cast<size_t>(geometry.inlier_matches.rows()),
              info.num_inliers);
    const TwoViewGeometry reversed = database.ReadTwoViewGeometry(id2, id1);
    EXPECT_EQ(reversed.inlier_matches.col(0), geometry.inlier_matches.col(1));
    EXPECT_EQ(reversed.inlier_matches.col(1), geometry.inlier_matches.col(0));
  }
  EXPECT_EQ(num_verified, 6u) << "the overlapping crops should all verify";

  for (const image_pair_t pair_id : database.ReadMatchedPairIds()) {
    const auto [id1, id2] = PairIdToImagePair(pair_id);
    const FeatureMatches matches = database.ReadMatches(id1, id2);
    EXPECT_EQ(matches.rows(),
              QuerySqlInt(Path(),
                          "SELECT rows FROM matches WHERE pair_id = " +
                              std::to_string(pair_id)));
    EXPECT_GT(matches.rows(), 0);
    // Column 0 indexes the smaller id's keypoints; reversed requests swap.
    EXPECT_LT(matches.col(0).maxCoeff(), database.NumKeypointsForImage(id1));
    EXPECT_LT(matches.col(1).maxCoeff(), database.NumKeypointsForImage(id2));
    const FeatureMatches reversed = database.ReadMatches(id2, id1);
    EXPECT_EQ(reversed.col(0), matches.col(1));
    EXPECT_EQ(reversed.col(1), matches.col(0));
    EXPECT_TRUE(database.ExistsMatches(id2, id1));
  }

  // The crops are shifted copies, so matched keypoints differ by the crop
  // offset: view_i is offset by (60 i, 45 i). Check one verified pair.
  const image_t id_a = database.ReadImageWithName("view_0.jpg").image_id;
  const image_t id_b = database.ReadImageWithName("view_1.jpg").image_id;
  const FeatureMatches matches =
      database.ReadTwoViewGeometry(id_a, id_b).inlier_matches;
  const FeatureKeypoints keypoints_a = database.ReadKeypoints(id_a);
  const FeatureKeypoints keypoints_b = database.ReadKeypoints(id_b);
  ASSERT_GT(matches.rows(), 15);
  size_t num_consistent = 0;
  for (Eigen::Index i = 0; i < matches.rows(); ++i) {
    const float dx =
        keypoints_a(matches(i, 0), 0) - keypoints_b(matches(i, 1), 0);
    const float dy =
        keypoints_a(matches(i, 0), 1) - keypoints_b(matches(i, 1), 1);
    num_consistent +=
        std::abs(dx - 60.0f) < 2.0f && std::abs(dy - 45.0f) < 2.0f;
  }
  EXPECT_GT(num_consistent, 0.9 * matches.rows());
}

TEST_F(ColmapDatabase, ReadOnlyLeavesFileUnchanged) {
  struct stat before_stat;
  ASSERT_EQ(stat(Path().c_str(), &before_stat), 0);
  std::ifstream before_file(Path(), std::ios::binary);
  const std::string before(std::istreambuf_iterator<char>(before_file), {});
  {
    DatabaseInspector database(Path());
    for (const DatabaseImage& image : database.ReadAllImages()) {
      database.ReadKeypoints(image.image_id);
      database.ReadDescriptors(image.image_id);
    }
    for (const TwoViewGeometryInfo& info :
         database.ReadTwoViewGeometryInfos()) {
      const auto [id1, id2] = PairIdToImagePair(info.pair_id);
      database.ReadTwoViewGeometry(id2, id1);
      database.ReadMatches(id2, id1);
    }
    EXPECT_THROW(database.UpdateCamera(database.ReadAllCameras().at(0)), Error);
  }
  struct stat after_stat;
  ASSERT_EQ(stat(Path().c_str(), &after_stat), 0);
  std::ifstream after_file(Path(), std::ios::binary);
  const std::string after(std::istreambuf_iterator<char>(after_file), {});
  EXPECT_EQ(before, after);
  EXPECT_EQ(before_stat.st_mtim.tv_sec, after_stat.st_mtim.tv_sec);
  EXPECT_EQ(before_stat.st_mtim.tv_nsec, after_stat.st_mtim.tv_nsec);
  EXPECT_EQ(before_stat.st_size, after_stat.st_size);
}

}  // namespace
}  // namespace colmap_gcn
