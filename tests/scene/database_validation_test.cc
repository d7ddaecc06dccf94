// The rows COLMAP 3.8 aborts on instead of reporting an error, each named
// with its image before COLMAP sees the database.

#include "scene/database_validation.h"

#include <gtest/gtest.h>

#include "scene/colmap_scene_fixture.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using test::ExecuteSql;

class DatabaseValidation : public testing::Test {
 protected:
  // Two images of camera 1 (SIMPLE_RADIAL, 4 parameters) with 3 keypoints (4
  // columns, as COLMAP writes them) and 3 SIFT descriptors each; image 3 has no
  // features yet.
  void SetUp() override {
    path_ = JoinPaths(dir_.Path(), "db.db");
    ExecuteSql(
        path_,
        std::string(test::kColmap38Schema) +
            "INSERT INTO cameras VALUES (1, 2, 640, 480, zeroblob(32), 0);"
            "INSERT INTO images (image_id, name, camera_id) VALUES "
            "(1, 'a.jpg', 1), (2, 'b.jpg', 1), (3, 'c.jpg', 1);"
            "INSERT INTO keypoints VALUES "
            "(1, 3, 4, zeroblob(48)), (2, 3, 4, zeroblob(48));"
            "INSERT INTO descriptors VALUES "
            "(1, 3, 128, zeroblob(384)), (2, 3, 128, zeroblob(384));");
  }

  // The message of the Error the check throws ("" for none).
  std::string Problem() const {
    try {
      ValidateDatabaseForColmap(Database(path_));
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_EQ(message.rfind("database " + path_ + ": ", 0), 0u) << message;
      EXPECT_NE(message.find("; COLMAP would abort on it"), std::string::npos)
          << message;
      return message;
    }
    return "";
  }

  void ExpectProblem(const std::string& sql, const std::string& expected) {
    ExecuteSql(path_, sql);
    const std::string problem = Problem();
    EXPECT_NE(problem.find(expected), std::string::npos)
        << "expected \"" << expected << "\" in: " << problem;
  }

  TemporaryDirectory dir_{"colmap_gcn_database_validation"};
  std::string path_;
};

TEST_F(DatabaseValidation, ConsistentDatabasePasses) {
  EXPECT_EQ(Problem(), "");
  // Empty feature rows as COLMAP writes them (and NULL blobs) are fine too.
  ExecuteSql(path_,
             "INSERT INTO keypoints VALUES (3, 0, 6, NULL);"
             "INSERT INTO descriptors VALUES (3, 0, 128, x'');");
  EXPECT_EQ(Problem(), "");
}

TEST_F(DatabaseValidation, ImageOfADeletedCamera) {
  ExpectProblem(
      "INSERT INTO cameras VALUES (7, 0, 640, 480, NULL, 0);"
      "UPDATE images SET camera_id = 7 WHERE image_id = 3;"
      "DELETE FROM cameras WHERE camera_id = 7;",
      "image \"c.jpg\" (id 3) refers to camera 7, which is not in the cameras "
      "table; COLMAP would abort on it");
}

TEST_F(DatabaseValidation, EveryBadImageIsCountedTheFirstNamed) {
  ExpectProblem("DELETE FROM cameras;",
                "image \"a.jpg\" (id 1) refers to camera 1, which is not in "
                "the cameras table (and 2 more images with such problems)");
}

TEST_F(DatabaseValidation, UnknownCameraModel) {
  ExpectProblem("UPDATE cameras SET model = 42;",
                "image \"a.jpg\" (id 1) uses camera 1, which has model id 42, "
                "unknown to COLMAP 3.8 (ids 0-10)");
}

TEST_F(DatabaseValidation, UnusedCameraOfUnknownModel) {
  ExpectProblem(
      "INSERT INTO cameras VALUES (5, -1, 640, 480, NULL, 0);",
      "database " + path_ +
          ": camera 5 has model id -1, unknown to COLMAP 3.8 (ids 0-10)");
}

// COLMAP 3.8 checks the parameter count when it reads the cameras.
TEST_F(DatabaseValidation, CameraParameterCount) {
  ExpectProblem("UPDATE cameras SET params = NULL;",
                "image \"a.jpg\" (id 1) uses camera 1, which has 0 bytes of "
                "parameters, not the 4 doubles of model SIMPLE_RADIAL");
}

TEST_F(DatabaseValidation, KeypointColumns) {
  ExpectProblem(
      "UPDATE keypoints SET cols = 3, data = zeroblob(36) "
      "WHERE image_id = 2;",
      "image \"b.jpg\" (id 2) has keypoints with 3 columns; COLMAP "
      "reads 2, 4 or 6");
}

TEST_F(DatabaseValidation, DescriptorColumns) {
  ExpectProblem(
      "UPDATE descriptors SET cols = 64, data = zeroblob(192) "
      "WHERE image_id = 1;",
      "image \"a.jpg\" (id 1) has descriptors with 64 columns; "
      "COLMAP 3.8 reads 128 (SIFT)");
}

TEST_F(DatabaseValidation, BlobSizes) {
  ExpectProblem("UPDATE keypoints SET data = zeroblob(47) WHERE image_id = 2;",
                "image \"b.jpg\" (id 2) has a keypoints blob of 47 bytes, not "
                "the 48 its shape 3x4 needs");
}

TEST_F(DatabaseValidation, DescriptorBlobSize) {
  ExpectProblem("UPDATE descriptors SET rows = 4 WHERE image_id = 1;",
                "image \"a.jpg\" (id 1) has a descriptors blob of 384 bytes, "
                "not the 512 its shape 4x128 needs");
}

TEST_F(DatabaseValidation, NegativeRows) {
  ExpectProblem("UPDATE keypoints SET rows = -3 WHERE image_id = 1;",
                "image \"a.jpg\" (id 1) has keypoints with -3 rows");
}

TEST_F(DatabaseValidation, KeypointAndDescriptorCountsDiffer) {
  ExpectProblem(
      "UPDATE descriptors SET rows = 2, data = zeroblob(256) "
      "WHERE image_id = 2;",
      "image \"b.jpg\" (id 2) has 3 keypoints but 2 descriptors");
}

}  // namespace
}  // namespace colmap_gcn
