// Databases in states other programs leave them in, through the built
// `colmap` front end: rows COLMAP 3.8 would abort on, the hot rollback
// journal of a crashed writer, a database never matched, too few images.
// Each is one "ERROR: " line naming the problem (exit 1) with nothing
// written, or, for a hot journal that can be rolled back, a warning and a
// normal run. Only the cases that run COLMAP skip without it.

#include <sys/stat.h>

#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "frontend_command.h"
#include "retrieval_test_utils.h"
#include "scene/colmap_scene_fixture.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

using test::CommandResult;
using test::ExecuteSql;
using test::ExpectOneLineError;
using test::QuerySqlInt;
using test::RealColmapExe;
using test::RunColmap;
using test::RunShell;

// Image 3 ("image2.jpg") of camera 7, which was deleted.
const char* const kDeleteCameraOfImage3 =
    "INSERT INTO cameras VALUES (7, 0, 640, 480, NULL, 0);"
    "UPDATE images SET camera_id = 7 WHERE image_id = 3;"
    "DELETE FROM cameras WHERE camera_id = 7;";

// What a crashed writer in rollback-journal mode did before dying.
const char* const kCrashedTransaction =
    "UPDATE images SET name = 'crashed_' || name;"
    "CREATE TABLE junk (x BLOB);"
    "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n "
    "WHERE i < 500) INSERT INTO junk SELECT randomblob(1000) FROM n;";

class DatabaseState : public testing::Test {
 protected:
  // A database of `num_images` images with descriptors, in rollback-journal
  // mode (as hloc and pycolmap write them).
  std::string MakeDatabase(const int num_images = 3) {
    const std::string path = JoinPaths(dir_.Path(), "db.db");
    std::vector<std::pair<std::string, FeatureDescriptors>> images;
    for (int i = 0; i < num_images; ++i) {
      images.emplace_back("image" + std::to_string(i) + ".jpg",
                          test::RandomDescriptors(40, 4, 10 + i));
    }
    test::CreateDescriptorDatabase(path, images);
    return path;
  }

  CommandResult Matcher(const std::string& path) {
    return RunColmap(
        "gcn_matcher --GcnMatching.pairing exhaustive "
        "--SiftMatching.use_gpu 0 --database_path " +
        ShellQuote(path));
  }

  TemporaryDirectory dir_{"colmap_gcn_database_state"};
};

// COLMAP 3.8 aborted on such a database (std::out_of_range from its camera
// lookup), the message promised a resume, and every rerun aborted again
// beside a new .gcn-partial; now nothing is made and the image is named.
TEST_F(DatabaseState, MatcherRefusesAnImageOfADeletedCamera) {
  const std::string path = MakeDatabase();
  ExecuteSql(path, kDeleteCameraOfImage3);
  const std::string before = ReadTextFile(path);
  ExpectOneLineError(Matcher(path),
                     {"database " + path,
                      "image \"image2.jpg\" (id 3) refers to camera 7, which "
                      "is not in the cameras table; COLMAP would abort on it"});
  EXPECT_FALSE(ExistsFile(path + ".gcn-partial"));
  EXPECT_FALSE(ExistsFile(path + ".gcn-partial.source"));
  EXPECT_FALSE(ExistsFile(path + ".pairs.txt"));
  EXPECT_EQ(ReadTextFile(path), before);
}

TEST_F(DatabaseState, MatcherRollsBackAHotJournal) {
  if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
  const std::string path = MakeDatabase();
  test::LeaveHotJournal(path, kCrashedTransaction);
  // Every read-only open fails until SQLite rolls the journal back.
  EXPECT_NE(RunShell("sqlite3 -readonly " + ShellQuote(path) +
                     " 'SELECT COUNT(*) FROM images;'"),
            0);
  const CommandResult result = Matcher(path);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.err.find("had an unfinished transaction of a program that "
                            "crashed"),
            std::string::npos)
      << result.err;
  EXPECT_EQ(result.err.find("ERROR"), std::string::npos) << result.err;
  EXPECT_FALSE(ExistsFile(path + "-journal"));
  EXPECT_FALSE(ExistsFile(path + ".gcn-partial"));
  EXPECT_EQ(QuerySqlInt(path,
                        "SELECT COUNT(*) FROM images WHERE name LIKE "
                        "'crashed_%';"),
            0);
  EXPECT_EQ(QuerySqlInt(path,
                        "SELECT COUNT(*) FROM sqlite_master WHERE name = "
                        "'junk';"),
            0);
  // Every pair of the 3 images was matched.
  EXPECT_EQ(QuerySqlInt(path, "SELECT COUNT(*) FROM matches;"), 3);
}

// Without write permission the journal cannot be rolled back: the line says
// what it is and how to recover, not just "read-only".
TEST_F(DatabaseState, MatcherExplainsAHotJournalItCannotRollBack) {
  const std::string path = MakeDatabase();
  test::LeaveHotJournal(path, kCrashedTransaction);
  chmod(path.c_str(), 0444);
  const std::string before = ReadTextFile(path);
  const std::string journal = ReadTextFile(path + "-journal");
  ExpectOneLineError(
      Matcher(path),
      {path + "-journal is the rollback journal of a transaction a crashed "
              "program left unfinished",
       "make " + path + " and its folder writable and run again"});
  ExpectOneLineError(
      RunColmap("gcn_adaptive_simulator --database_path " + ShellQuote(path)),
      {path + "-journal is the rollback journal"});
  EXPECT_EQ(ReadTextFile(path), before);
  EXPECT_EQ(ReadTextFile(path + "-journal"), journal);
  EXPECT_FALSE(ExistsFile(path + ".gcn-partial"));
  chmod(path.c_str(), 0644);
}

// The simulator replays verification from two_view_geometries: without any
// row every pair would count as failed and it printed a table of zeros.
TEST_F(DatabaseState, AdaptiveSimulatorRefusesANeverMatchedDatabase) {
  const std::string path = MakeDatabase();
  const std::string before = ReadTextFile(path);
  const CommandResult result =
      RunColmap("gcn_adaptive_simulator --database_path " + ShellQuote(path));
  ExpectOneLineError(result,
                     {"database " + path + " was never matched",
                      "two_view_geometries table is empty",
                      "run colmap exhaustive_matcher on it first"});
  EXPECT_EQ(result.out, "");
  EXPECT_EQ(ReadTextFile(path), before);
}

TEST_F(DatabaseState, MatcherNeedsTwoImagesNotFeatureExtraction) {
  const std::string path = MakeDatabase(1);
  const CommandResult result = Matcher(path);
  ExpectOneLineError(result,
                     {path + " has 1 image; matching needs at least 2"});
  EXPECT_EQ(result.err.find("feature_extractor"), std::string::npos)
      << result.err;
  EXPECT_FALSE(ExistsFile(path + ".gcn-partial"));
}

}  // namespace
}  // namespace colmap_gcn
