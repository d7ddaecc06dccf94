// Copying, checkpointing and replacing databases in the states COLMAP leaves
// them in: committed data still in "-wal" after a killed writer, stale side
// files of an earlier copy, damaged copies, symlinks, read-only files.

#include "scene/database_copy.h"

#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include <gtest/gtest.h>

#include "scene/colmap_scene_fixture.h"
#include "scene/database.h"
#include "scene/database_working_copy.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"
#include "util/file_lock.h"

namespace colmap_gcn {
namespace {

namespace fs = std::filesystem;
using test::ExecuteSql;
using test::ExpectErrorContaining;
using test::kColmap38Schema;
using test::LeaveCommittedDataInWal;
using test::LeaveHotJournal;
using test::QuerySqlInt;

// A COLMAP-layout database in WAL mode with `num_images` images.
void CreateDatabase(const std::string& path, const int num_images) {
  ExecuteSql(path, std::string("PRAGMA journal_mode=WAL;") + kColmap38Schema);
  for (int i = 1; i <= num_images; ++i) {
    ExecuteSql(path,
               "INSERT INTO cameras VALUES (" + std::to_string(i) +
                   ", 0, 640, 480, NULL, 0);"
                   "INSERT INTO images (image_id, name, camera_id) VALUES (" +
                   std::to_string(i) + ", 'img" + std::to_string(i) +
                   ".jpg', " + std::to_string(i) + ");");
  }
}

int64_t NumGeometries(const std::string& path) {
  return QuerySqlInt(path, "SELECT COUNT(*) FROM two_view_geometries;");
}

const char* const kTwoGeometries =
    "INSERT INTO two_view_geometries (pair_id, rows, cols, config) VALUES "
    "(2147483649, 0, 2, 2), (2147483650, 0, 2, 2);";

class DatabaseFiles : public testing::Test {
 protected:
  void SetUp() override {
    base_ = JoinPaths(dir_.Path(), "base.db");
    CreateDatabase(base_, 3);
    crashed_ = JoinPaths(dir_.Path(), "crashed.db");
    const std::string writer = JoinPaths(dir_.Path(), "writer.db");
    fs::copy_file(base_, writer);
    LeaveCommittedDataInWal(writer, kTwoGeometries, crashed_);
  }

  TemporaryDirectory dir_{"colmap_gcn_database_copy"};
  std::string base_;
  std::string crashed_;
};

TEST_F(DatabaseFiles, ThePlainMainFileLacksWhatTheWalHolds) {
  // Why a file copy is wrong: the main file alone has no geometries.
  const std::string main_only = JoinPaths(dir_.Path(), "main_only.db");
  fs::copy_file(crashed_, main_only);
  EXPECT_EQ(NumGeometries(main_only), 0);
  EXPECT_EQ(NumGeometries(crashed_), 2);
}

TEST_F(DatabaseFiles, CopyKeepsCommittedWalContent) {
  const std::string copy = JoinPaths(dir_.Path(), "copy.db");
  CopyDatabase(crashed_, copy);
  EXPECT_FALSE(ExistsFile(copy + "-wal") && fs::file_size(copy + "-wal") > 0);
  EXPECT_EQ(NumGeometries(copy), 2);
  EXPECT_EQ(CheckDatabaseIntegrity(copy), "");
}

TEST_F(DatabaseFiles, CopyRemovesStaleSideFilesOfTheTarget) {
  // The "-wal" of another database beside the target would be replayed onto
  // the fresh copy and corrupt it.
  const std::string copy = JoinPaths(dir_.Path(), "copy.db");
  fs::copy_file(crashed_ + "-wal", copy + "-wal");
  fs::copy_file(crashed_ + "-shm", copy + "-shm");
  CopyDatabase(base_, copy);
  EXPECT_EQ(CheckDatabaseIntegrity(copy), "");
  EXPECT_EQ(NumGeometries(copy), 0);
  EXPECT_EQ(QuerySqlInt(copy, "SELECT COUNT(*) FROM images;"), 3);
}

TEST_F(DatabaseFiles, EmptySideFilesGoAWalWithContentStays) {
  // A "-wal" with committed content is the database's data: kept.
  RemoveEmptySqliteSideFiles(crashed_);
  EXPECT_TRUE(ExistsFile(crashed_ + "-wal"));
  EXPECT_EQ(NumGeometries(crashed_), 2);
  // Empty ones, reached through a symbolic link, go.
  WriteFileAtomically(base_ + "-wal", "");
  WriteFileAtomically(base_ + "-shm", "index");
  const std::string link = JoinPaths(dir_.Path(), "link.db");
  fs::create_symlink(base_, link);
  RemoveEmptySqliteSideFiles(link);
  EXPECT_FALSE(ExistsFile(base_ + "-wal"));
  EXPECT_FALSE(ExistsFile(base_ + "-shm"));
  EXPECT_EQ(QuerySqlInt(base_, "SELECT COUNT(*) FROM images;"), 3);
}

TEST_F(DatabaseFiles, CopyKeepsThePermissionBits) {
  chmod(base_.c_str(), 0640);
  const std::string copy = JoinPaths(dir_.Path(), "copy.db");
  CopyDatabase(base_, copy);
  struct stat info;
  ASSERT_EQ(stat(copy.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0640u);
}

TEST_F(DatabaseFiles, CopyOfAMissingDatabaseFails) {
  ExpectErrorContaining(
      [&] { CopyDatabase(JoinPaths(dir_.Path(), "none.db"), base_ + "2"); },
      "none.db");
}

TEST_F(DatabaseFiles, CheckpointFoldsTheWalIntoTheMainFile) {
  CheckpointDatabase(crashed_);
  const std::string main_only = JoinPaths(dir_.Path(), "main_only.db");
  fs::copy_file(crashed_, main_only);
  EXPECT_EQ(NumGeometries(main_only), 2);
  EXPECT_TRUE(!ExistsFile(crashed_ + "-wal") ||
              fs::file_size(crashed_ + "-wal") == 0);
}

TEST_F(DatabaseFiles, IntegrityCheckFindsDamage) {
  // Enough rows for several pages, then garbage over an inner page.
  std::string sql = "BEGIN;";
  for (int i = 0; i < 2000; ++i) {
    sql +=
        "INSERT INTO two_view_geometries (pair_id, rows, cols, config) "
        "VALUES (" +
        std::to_string(100000 + i) + ", 0, 2, 2);";
  }
  ExecuteSql(base_, sql + "COMMIT; PRAGMA wal_checkpoint(TRUNCATE);");
  EXPECT_EQ(CheckDatabaseIntegrity(base_), "");
  {
    FILE* file = std::fopen(base_.c_str(), "r+b");
    ASSERT_NE(file, nullptr);
    const size_t size = fs::file_size(base_);
    std::fseek(file, static_cast<long>(size / 2), SEEK_SET);
    const std::string garbage(4096, '\x5a');
    std::fwrite(garbage.data(), 1, garbage.size(), file);
    std::fclose(file);
  }
  EXPECT_NE(CheckDatabaseIntegrity(base_), "");
  EXPECT_NE(CheckDatabaseIntegrity(JoinPaths(dir_.Path(), "absent.db")), "");
}

TEST_F(DatabaseFiles, WorkingCopyStartsFromTheWalAndReplacesOnCommit) {
  {
    DatabaseWorkingCopy copy(crashed_);
    EXPECT_FALSE(copy.Resumed());
    EXPECT_EQ(NumGeometries(copy.Path()), 2);
    ExecuteSql(copy.Path(),
               "INSERT INTO two_view_geometries (pair_id, rows, cols, config) "
               "VALUES (4294967299, 0, 2, 2);");
    copy.Commit();
    EXPECT_FALSE(ExistsFile(copy.Path()));
    EXPECT_FALSE(ExistsFile(crashed_ + ".gcn-partial.source"));
  }
  EXPECT_EQ(NumGeometries(crashed_), 3);
  EXPECT_EQ(CheckDatabaseIntegrity(crashed_), "");
}

TEST_F(DatabaseFiles, WorkingCopyResumesWhileTheDatabaseIsUnchanged) {
  std::string copy_path;
  {
    DatabaseWorkingCopy copy(base_);
    copy_path = copy.Path();
    copy.MarkWritten();
    ExecuteSql(copy_path,
               "INSERT INTO two_view_geometries (pair_id, rows, cols, config) "
               "VALUES (4294967299, 0, 2, 2);");
    // Interrupted: no Commit.
  }
  {
    DatabaseWorkingCopy copy(base_);
    EXPECT_TRUE(copy.Resumed());
    EXPECT_EQ(NumGeometries(copy.Path()), 1);
  }
  // The user changed the database meanwhile: the copy is made anew.
  ExecuteSql(base_, kTwoGeometries);
  DatabaseWorkingCopy copy(base_);
  EXPECT_FALSE(copy.Resumed());
  EXPECT_EQ(NumGeometries(copy.Path()), 2);
}

TEST_F(DatabaseFiles, WorkingCopyNothingWasWrittenIntoIsRemoved) {
  std::string copy_path;
  {
    DatabaseWorkingCopy copy(base_);
    copy_path = copy.Path();
    EXPECT_TRUE(ExistsFile(copy_path));
    // A failure before COLMAP ran: nothing to resume.
  }
  EXPECT_FALSE(ExistsFile(copy_path));
  EXPECT_FALSE(ExistsFile(base_ + ".gcn-partial.source"));
  for (const char* suffix : kDatabaseSideFileSuffixes) {
    EXPECT_FALSE(ExistsFile(copy_path + suffix)) << suffix;
  }
}

TEST_F(DatabaseFiles, WorkingCopyDiscardsADamagedCopy) {
  std::string copy_path;
  {
    DatabaseWorkingCopy copy(base_);
    copy.MarkWritten();
    copy_path = copy.Path();
  }
  WriteFileAtomically(copy_path, std::string(8192, 'x'));
  testing::internal::CaptureStderr();
  DatabaseWorkingCopy copy(base_);
  const std::string message = testing::internal::GetCapturedStderr();
  EXPECT_FALSE(copy.Resumed());
  EXPECT_NE(message.find("discarding"), std::string::npos) << message;
  EXPECT_EQ(CheckDatabaseIntegrity(copy.Path()), "");
  EXPECT_EQ(QuerySqlInt(copy.Path(), "SELECT COUNT(*) FROM images;"), 3);
}

TEST_F(DatabaseFiles, WorkingCopyRefusesWhenTheDatabaseChangedMeanwhile) {
  DatabaseWorkingCopy copy(base_);
  ExecuteSql(base_, kTwoGeometries);
  ExpectErrorContaining([&] { copy.Commit(); }, "changed by another program");
  EXPECT_EQ(NumGeometries(base_), 2);
  EXPECT_TRUE(ExistsFile(copy.Path()));
}

TEST_F(DatabaseFiles, WorkingCopyWritesThroughASymlink) {
  const std::string link = JoinPaths(dir_.Path(), "link.db");
  fs::create_symlink(base_, link);
  {
    DatabaseWorkingCopy copy(link);
    EXPECT_EQ(copy.DatabasePath(), fs::canonical(base_).string());
    ExecuteSql(copy.Path(), kTwoGeometries);
    copy.Commit();
  }
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(NumGeometries(base_), 2);
}

TEST_F(DatabaseFiles, ReadOnlyDatabaseOrFolderIsRefusedUpFront) {
  chmod(base_.c_str(), 0444);
  ExpectErrorContaining([&] { CheckDatabaseWritable(base_); },
                        "is read-only (mode 0444)");
  ExpectErrorContaining([&] { DatabaseWorkingCopy copy(base_); }, "read-only");
  EXPECT_FALSE(ExistsFile(base_ + ".gcn-partial"));
  chmod(base_.c_str(), 0644);

  const std::string folder = JoinPaths(dir_.Path(), "locked");
  CreateDirIfNotExists(folder);
  const std::string inside = JoinPaths(folder, "db.db");
  CreateDatabase(inside, 1);
  chmod(folder.c_str(), 0555);
  ExpectErrorContaining([&] { CheckDatabaseWritable(inside); },
                        "folder " + folder);
  chmod(folder.c_str(), 0755);
}

TEST_F(DatabaseFiles, MissingDatabaseIsNamed) {
  ExpectErrorContaining(
      [&] { ResolveDatabasePath(JoinPaths(dir_.Path(), "none.db")); },
      "none.db does not exist");
  const std::string dangling = JoinPaths(dir_.Path(), "dangling.db");
  fs::create_symlink(JoinPaths(dir_.Path(), "gone.db"), dangling);
  ExpectErrorContaining([&] { ResolveDatabasePath(dangling); },
                        "dangling.db does not exist");
}

// chmod u+w is only the answer for the file's owner when its own write bit is
// missing. Root passes access() on any file, so as root the other case is a
// file chowned to someone else without write bits (refused even for root);
// as another user it is a file of root's.
TEST_F(DatabaseFiles, ReadOnlyHintFitsWhoMayWriteTheFile) {
  chmod(base_.c_str(), 0444);
  try {
    CheckDatabaseWritable(base_);
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("(chmod u+w)"), std::string::npos)
        << error.what();
  }
  std::string foreign = "/etc/passwd";
  const uid_t uid = geteuid();
  if (uid == 0) {
    foreign = JoinPaths(dir_.Path(), "foreign.db");
    CreateDatabase(foreign, 1);
    ASSERT_EQ(chown(foreign.c_str(), 12345, 12345), 0);
    chmod(foreign.c_str(), 0444);
  }
  struct stat info;
  ASSERT_EQ(stat(foreign.c_str(), &info), 0);
  ASSERT_NE(info.st_uid, uid);
  try {
    CheckDatabaseWritable(foreign);
    ADD_FAILURE() << "no error for " << foreign;
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("is owned by uid " + std::to_string(info.st_uid) +
                           ", not writable by uid " + std::to_string(uid)),
              std::string::npos)
        << message;
    EXPECT_EQ(message.find("chmod"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// A database in rollback-journal mode, as hloc, pycolmap and older COLMAP
// write, with a hot journal of a crashed writer beside it that renamed every
// image and added a table.
std::string CrashedRollbackJournalDatabase(const std::string& dir) {
  const std::string path = JoinPaths(dir, "journal.db");
  ExecuteSql(path,
             std::string(kColmap38Schema) +
                 "INSERT INTO cameras VALUES (1, 0, 640, 480, NULL, 0);"
                 "INSERT INTO images (image_id, name, camera_id) VALUES "
                 "(1, 'a.jpg', 1), (2, 'b.jpg', 1);");
  LeaveHotJournal(path,
                  "UPDATE images SET name = 'crashed_' || name;"
                  "CREATE TABLE junk (x BLOB);"
                  "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 "
                  "FROM n WHERE i < 500) "
                  "INSERT INTO junk SELECT randomblob(1000) FROM n;");
  return path;
}

TEST(HotJournal, IsRolledBackWithAWarning) {
  TemporaryDirectory dir("colmap_gcn_hot_journal");
  const std::string path = CrashedRollbackJournalDatabase(dir.Path());
  // What every read-only open meets, SQLite's own and ours.
  ExpectErrorContaining(
      [&] { QuerySqlInt(path, "SELECT COUNT(*) FROM images;"); },
      "attempt to write a readonly database");
  ExpectErrorContaining([&] { Database database(path); },
                        path +
                            "-journal is the rollback journal of a "
                            "transaction a crashed program left "
                            "unfinished");
  test::LogLines log;
  {
    const ScopedLogSink sink(&log);
    RecoverHotJournal(path);
  }
  ASSERT_EQ(log.size(), 1u);
  EXPECT_NE(log[0].find("unfinished transaction"), std::string::npos) << log[0];
  EXPECT_NE(log[0].find("rolled it back"), std::string::npos) << log[0];
  EXPECT_FALSE(ExistsFile(path + "-journal"));
  // The state before the crashed transaction.
  EXPECT_EQ(QuerySqlInt(path,
                        "SELECT COUNT(*) FROM images WHERE name LIKE "
                        "'crashed_%';"),
            0);
  EXPECT_EQ(QuerySqlInt(path,
                        "SELECT COUNT(*) FROM sqlite_master WHERE "
                        "name = 'junk';"),
            0);
  EXPECT_EQ(Database(path).NumImages(), 2u);
  EXPECT_EQ(CheckDatabaseIntegrity(path), "");
  // Nothing left to do: no second warning.
  {
    const ScopedLogSink sink(&log);
    RecoverHotJournal(path);
  }
  EXPECT_EQ(log.size(), 1u);
}

// Without write permission on the file (a missing write bit counts even for
// root) or its folder, SQLite cannot roll back: the line says what the
// journal is and how to recover, never just "read-only".
TEST(HotJournal, WithoutWritePermissionIsExplained) {
  TemporaryDirectory dir("colmap_gcn_hot_journal");
  const std::string path = CrashedRollbackJournalDatabase(dir.Path());
  const std::string before = ReadTextFile(path);
  const std::string journal = ReadTextFile(path + "-journal");
  const auto expect_refused = [&] {
    try {
      RecoverHotJournal(path);
      ADD_FAILURE() << "no error";
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_EQ(message, HotJournalMessage(path));
      EXPECT_NE(message.find("make " + path + " and its folder writable"),
                std::string::npos)
          << message;
      EXPECT_NE(
          message.find("`sqlite3 " + path + " 'PRAGMA integrity_check;'`"),
          std::string::npos)
          << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_EQ(ReadTextFile(path), before);
    EXPECT_EQ(ReadTextFile(path + "-journal"), journal);
  };
  chmod(path.c_str(), 0444);
  expect_refused();
  chmod(path.c_str(), 0644);
  chmod(dir.Path().c_str(), 0555);
  expect_refused();
  chmod(dir.Path().c_str(), 0755);
  RecoverHotJournal(path);
  EXPECT_FALSE(ExistsFile(path + "-journal"));
}

TEST(HotJournal, NoJournalIsANoOp) {
  TemporaryDirectory dir("colmap_gcn_hot_journal");
  const std::string path = JoinPaths(dir.Path(), "plain.db");
  ExecuteSql(path, kColmap38Schema);
  const std::string before = ReadTextFile(path);
  test::LogLines log;
  {
    const ScopedLogSink sink(&log);
    RecoverHotJournal(path);
    RecoverHotJournal(JoinPaths(dir.Path(), "missing.db"));
  }
  EXPECT_EQ(log.size(), 0u);
  EXPECT_EQ(ReadTextFile(path), before);
}

// Runs fn in a child process; returns its exit code.
int InChildProcess(const std::function<int()>& fn) {
  const pid_t pid = fork();
  if (pid == 0) _exit(fn());
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST_F(DatabaseFiles, LockKeepsOtherProcessesOut) {
  const std::string lock_path = DatabaseLockPath(base_);
  auto try_lock = [&] {
    try {
      ScopedFileLock lock(lock_path, "db.db");
      return 0;
    } catch (const Error& error) {
      const std::string message = error.what();
      return message.find("another gcn_matcher is using db.db (pid " +
                          std::to_string(getppid())) != std::string::npos
                 ? 1
                 : 2;
    }
  };
  {
    ScopedFileLock lock(lock_path, "db.db");
    // Re-entrant in this process, exclusive across processes.
    { ScopedFileLock again(lock_path, "db.db"); }
    EXPECT_EQ(InChildProcess(try_lock), 1);
  }
  EXPECT_FALSE(ExistsFile(lock_path));
  EXPECT_EQ(InChildProcess(try_lock), 0);
}

// The merge of merge_scenes.sh: ids offset past the earlier inputs', names
// prefixed as asked, pose priors kept, matches dropped.
TEST(MergeDatabases, OffsetsIdsPrefixesNamesKeepsPriors) {
  const TemporaryDirectory dir("colmap_gcn_merge");
  const std::string a = JoinPaths(dir.Path(), "a.db");
  const std::string b = JoinPaths(dir.Path(), "b.db");
  CreateDatabase(a, 2);
  CreateDatabase(b, 3);
  ExecuteSql(a, kTwoGeometries);
  ExecuteSql(b, "UPDATE images SET prior_tx = 7 WHERE image_id = 2;");
  const std::string merged = JoinPaths(dir.Path(), "merged.db");
  MergeDatabases({a, b}, merged, {"a__", "b__"});
  EXPECT_EQ(QuerySqlInt(merged, "SELECT COUNT(*) FROM images;"), 5);
  EXPECT_EQ(QuerySqlInt(merged, "SELECT COUNT(*) FROM cameras;"), 5);
  EXPECT_EQ(NumGeometries(merged), 0);
  EXPECT_EQ(QuerySqlInt(merged,
                        "SELECT image_id FROM images WHERE name = "
                        "'b__img2.jpg' AND camera_id = 4 AND prior_tx = 7;"),
            4);
  EXPECT_EQ(QuerySqlInt(merged,
                        "SELECT COUNT(*) FROM images WHERE name LIKE 'a__%';"),
            2);
  // Without prefixes: "<input index>/".
  const std::string numbered = JoinPaths(dir.Path(), "numbered.db");
  MergeDatabases({a, b}, numbered);
  EXPECT_EQ(QuerySqlInt(numbered,
                        "SELECT COUNT(*) FROM images WHERE name LIKE '1/%';"),
            3);
  ExpectErrorContaining(
      [&] {
        MergeDatabases({a, b}, JoinPaths(dir.Path(), "x.db"), {"a__"});
      },
      "merging 2 databases needs as many name prefixes (got 1)");
}

// --keep_matches: each input's pairs under the merged ids, none across.
TEST(MergeDatabases, KeepsEachInputsMatchesUnderTheMergedPairIds) {
  const TemporaryDirectory dir("colmap_gcn_merge_matches");
  const std::string a = JoinPaths(dir.Path(), "a.db");
  const std::string b = JoinPaths(dir.Path(), "b.db");
  CreateDatabase(a, 2);
  CreateDatabase(b, 3);
  ExecuteSql(a, kTwoGeometries);  // (1, 2) and (1, 3)
  ExecuteSql(b,
             "INSERT INTO two_view_geometries (pair_id, rows, cols, config) "
             "VALUES (4294967297, 5, 2, 2);"  // (2, 3)
             "INSERT INTO matches (pair_id, rows, cols) "
             "VALUES (4294967297, 7, 2);");
  const std::string merged = JoinPaths(dir.Path(), "merged.db");
  MergeDatabases({a, b}, merged, {"a__", "b__"}, /*keep_matches=*/true);
  EXPECT_EQ(NumGeometries(merged), 3);
  // b's images 2 and 3 are 4 and 5 in the merge: pair 4 * (2^31 - 1) + 5.
  EXPECT_EQ(QuerySqlInt(merged,
                        "SELECT rows FROM two_view_geometries WHERE pair_id "
                        "= 8589934593;"),
            5);
  EXPECT_EQ(QuerySqlInt(merged,
                        "SELECT rows FROM matches WHERE pair_id = "
                        "8589934593;"),
            7);
  EXPECT_EQ(QuerySqlInt(merged,
                        "SELECT COUNT(*) FROM two_view_geometries WHERE "
                        "pair_id = 2147483649;"),
            1);
  EXPECT_EQ(QuerySqlInt(merged,
                        "SELECT image_id FROM images WHERE name = "
                        "'b__img2.jpg';"),
            4);
}

}  // namespace
}  // namespace colmap_gcn
