// gcn_matcher against the states COLMAP, the user or the machine leave a
// database in: killed writers (committed data only in "-wal"), stale side
// files, symlinks, concurrent runs, read-only files, and gcn_matcher itself
// interrupted by SIGINT, SIGTERM and SIGKILL at three points of a run. Each
// case checks that no committed data is lost, the database passes SQLite's
// integrity check, and the re-run ends with the uninterrupted run's pairs.

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "e2e_scene.h"
#include "scene/colmap_scene_fixture.h"
#include "scene/database.h"
#include "scene/database_inspector.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

namespace fs = std::filesystem;
using test::DatabaseInspector;
using test::ExecuteSql;
using test::FrontendExe;
using test::GeometryPairIds;
using test::IntegrityCheck;
using test::LeaveCommittedDataInWal;
using test::QuerySqlInt;
using test::RealColmapExe;
using test::RunShell;
using test::TwoViewGeometry;

const int kNumImages = 8;
const int kNumPairs = kNumImages * (kNumImages - 1) / 2;
const int kBlockSize = 5;

// Our front end first on PATH, as users run it.
std::string PathWithFrontend() {
  const std::string bin = FrontendExe().substr(0, FrontendExe().rfind('/'));
  return "PATH=" + ShellQuote(bin) + ":$PATH";
}

std::string MatcherArgs(
    const std::string& database_path,
    const std::string& pairing = "--GcnMatching.pairing exhaustive",
    const int block_size = kBlockSize) {
  return " gcn_matcher --database_path " + ShellQuote(database_path) + " " +
         pairing + " --GcnMatching.block_size " + std::to_string(block_size) +
         " --SiftMatching.num_threads 1";
}

int Colmap(const std::string& args, std::string* output) {
  return RunShell(
      PathWithFrontend() + " " + ShellQuote(FrontendExe()) + " " + args,
      output);
}

int64_t NumGeometries(const std::string& path) {
  return QuerySqlInt(path, "SELECT COUNT(*) FROM two_view_geometries;");
}

// The database as the user finds it after a run: sound, one row per pair,
// a match row for every geometry, and nothing of ours left beside it.
void ExpectCompleteDatabase(const std::string& path,
                            const std::set<int64_t>& expected_pairs) {
  // First, before this test's own reads make them.
  EXPECT_FALSE(fs::exists(path + "-wal"));
  EXPECT_FALSE(fs::exists(path + "-shm"));
  EXPECT_EQ(IntegrityCheck(path), "ok");
  EXPECT_EQ(GeometryPairIds(path), expected_pairs);
  EXPECT_EQ(NumGeometries(path),
            QuerySqlInt(path,
                        "SELECT COUNT(DISTINCT pair_id) FROM "
                        "two_view_geometries;"));
  EXPECT_EQ(QuerySqlInt(path, "SELECT COUNT(*) FROM matches;"),
            static_cast<int64_t>(expected_pairs.size()));
  EXPECT_FALSE(fs::exists(path + ".gcn-partial"));
  EXPECT_FALSE(fs::exists(path + ".gcn-lock"));
}

// A gcn_matcher started in its own process group, as a shell job is.
class Job {
 public:
  Job(const std::string& args,
      const std::string& log_path,
      const std::string& env = "") {
    const std::string command = "export " + PathWithFrontend() + "; " + env +
                                " exec " + ShellQuote(FrontendExe()) + " " +
                                args + " > " + ShellQuote(log_path) + " 2>&1";
    pid_ = fork();
    if (pid_ == 0) {
      setpgid(0, 0);
      execl("/bin/sh", "sh", "-c", command.c_str(), nullptr);
      _exit(127);
    }
    setpgid(pid_, pid_);
  }

  pid_t Pid() const { return pid_; }

  // Process state letter from /proc ('T' stopped, 'Z' zombie), ' ' if gone.
  char State() const {
    std::ifstream stat("/proc/" + std::to_string(pid_) + "/stat");
    std::string line;
    if (!std::getline(stat, line)) return ' ';
    const size_t paren = line.rfind(')');
    return paren + 2 < line.size() ? line[paren + 2] : ' ';
  }

  bool HasChild() const {
    for (const auto& entry : fs::directory_iterator("/proc")) {
      std::ifstream stat(entry.path() / "stat");
      std::string line;
      if (!std::getline(stat, line)) continue;
      const size_t paren = line.rfind(')');
      if (paren == std::string::npos) continue;
      std::istringstream fields(line.substr(paren + 2));
      char state;
      pid_t parent = 0;
      fields >> state >> parent;
      if (parent == pid_) return true;
    }
    return false;
  }

  // Polls condition every 20 ms for at most two minutes, or until the
  // process has ended.
  bool WaitFor(const std::function<bool()>& condition) const {
    for (int i = 0; i < 6000; ++i) {
      if (condition()) return true;
      if (State() == ' ' || State() == 'Z') return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  void SignalGroup(const int signal_number) const {
    killpg(pid_, signal_number);
  }

  int Wait() {
    int status = 0;
    waitpid(pid_, &status, 0);
    return status;
  }

 private:
  pid_t pid_ = -1;
};

class DatabaseSafety : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (RealColmapExe().empty()) return;
    dir_ = new TemporaryDirectory("colmap_gcn_safety");
    std::string output;
    const std::string scene = JoinPaths(dir_->Path(), "scene");
    ASSERT_EQ(Colmap("gcn_synth --output_path " + scene +
                         " --GcnSynth.family ordinary --GcnSynth.num_images " +
                         std::to_string(kNumImages) + " --GcnSynth.seed 3",
                     &output),
              0)
        << output;
    ASSERT_EQ(Colmap("feature_extractor --database_path " + BasePath() +
                         " --image_path " + scene +
                         "/images --ImageReader.single_camera 1"
                         " --SiftExtraction.max_num_features 512"
                         " --SiftExtraction.num_threads 1"
                         " --SiftExtraction.use_gpu 0",
                     &output),
              0)
        << output;
    const std::string reference = CopyOfBase("reference.db");
    ASSERT_EQ(Colmap(MatcherArgs(reference), &output), 0) << output;
    *reference_pairs_ = GeometryPairIds(reference);
    ASSERT_EQ(reference_pairs_->size(), static_cast<size_t>(kNumPairs));
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  void SetUp() override {
    if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
    ASSERT_NE(dir_, nullptr);
    ASSERT_EQ(reference_pairs_->size(), static_cast<size_t>(kNumPairs));
  }

  static std::string BasePath() { return JoinPaths(dir_->Path(), "base.db"); }
  static std::string Path(const std::string& name) {
    return JoinPaths(dir_->Path(), name);
  }
  static std::string CopyOfBase(const std::string& name) {
    fs::copy_file(BasePath(), Path(name), fs::copy_options::overwrite_existing);
    return Path(name);
  }

  static TemporaryDirectory* dir_;
  static std::set<int64_t>* reference_pairs_;
};

TemporaryDirectory* DatabaseSafety::dir_ = nullptr;
std::set<int64_t>* DatabaseSafety::reference_pairs_ = new std::set<int64_t>;

TEST_F(DatabaseSafety, MatchesCommittedOnlyToTheWalAreKept) {
  // Real matches for a few pairs, then the state a killed exhaustive_matcher
  // leaves after committing them: they exist only in "-wal".
  const std::string matched = CopyOfBase("some_matched.db");
  std::string output;
  // Imported pairs: the first image with every other one.
  const Database base(BasePath());
  const auto images = base.ReadAllImages();
  std::string pairs;
  for (size_t i = 1; i < images.size(); ++i) {
    pairs += images[0].name + " " + images[i].name + "\n";
  }
  WriteFileAtomically(Path("first_pairs.txt"), pairs);
  ASSERT_EQ(Colmap(MatcherArgs(matched,
                               "--GcnMatching.pairing imported"
                               " --GcnMatching.match_list_path " +
                                   Path("first_pairs.txt")),
                   &output),
            0)
      << output;
  const int64_t num_first = NumGeometries(matched);
  ASSERT_EQ(num_first, kNumImages - 1);

  const std::string writer = CopyOfBase("writer.db");
  const std::string crashed = Path("crashed_matcher.db");
  LeaveCommittedDataInWal(writer,
                          "ATTACH '" + matched +
                              "' AS m;"
                              "INSERT INTO matches SELECT * FROM m.matches;"
                              "INSERT INTO two_view_geometries SELECT * FROM "
                              "m.two_view_geometries;",
                          crashed);
  ASSERT_EQ(Colmap(MatcherArgs(crashed), &output), 0) << output;
  EXPECT_NE(output.find("(" + std::to_string(num_first) +
                        " of the pairs were already matched"),
            std::string::npos)
      << output;
  ExpectCompleteDatabase(crashed, *reference_pairs_);
  // The rows COLMAP had committed are the ones kept, not matched again.
  const DatabaseInspector before(matched);
  const DatabaseInspector after(crashed);
  for (const auto& info : before.ReadTwoViewGeometryInfos()) {
    const auto [id1, id2] = PairIdToImagePair(info.pair_id);
    const TwoViewGeometry kept = after.ReadTwoViewGeometry(id1, id2);
    const TwoViewGeometry original = before.ReadTwoViewGeometry(id1, id2);
    EXPECT_EQ(kept.config, original.config);
    EXPECT_EQ(kept.inlier_matches, original.inlier_matches);
    EXPECT_EQ(kept.F, original.F);
  }
}

TEST_F(DatabaseSafety, FeaturesCommittedOnlyToTheWalAreUsed) {
  // A killed feature_extractor: every image and feature only in "-wal".
  const std::string empty = Path("empty.db");
  std::string output;
  ASSERT_EQ(Colmap("database_creator --database_path " + empty, &output), 0)
      << output;
  const std::string crashed = Path("crashed_extractor.db");
  LeaveCommittedDataInWal(
      empty,
      "ATTACH '" + BasePath() +
          "' AS b;"
          "INSERT INTO cameras SELECT * FROM b.cameras;"
          "INSERT INTO images SELECT * FROM b.images;"
          "INSERT INTO keypoints SELECT * FROM b.keypoints;"
          "INSERT INTO descriptors SELECT * FROM b.descriptors;",
      crashed);
  ASSERT_EQ(Colmap(MatcherArgs(crashed), &output), 0) << output;
  ExpectCompleteDatabase(crashed, *reference_pairs_);
}

TEST_F(DatabaseSafety, StaleWalOfAnEarlierCopyIsNotReplayed) {
  const std::string database = CopyOfBase("stale.db");
  const std::string writer = CopyOfBase("stale_writer.db");
  LeaveCommittedDataInWal(
      writer,
      "INSERT INTO two_view_geometries (pair_id, rows, cols, config) VALUES "
      "(1, 0, 2, 2);",
      Path("stale_source.db"));
  fs::copy_file(Path("stale_source.db-wal"), database + ".gcn-partial-wal");
  fs::copy_file(Path("stale_source.db-shm"), database + ".gcn-partial-shm");
  std::string output;
  ASSERT_EQ(Colmap(MatcherArgs(database), &output), 0) << output;
  ExpectCompleteDatabase(database, *reference_pairs_);
}

TEST_F(DatabaseSafety, SymlinkedDatabaseReceivesTheMatches) {
  CreateDirIfNotExists(Path("real"));
  fs::copy_file(BasePath(), Path("real/database.db"));
  const std::string link = Path("link.db");
  fs::create_symlink(Path("real/database.db"), link);
  std::string output;
  ASSERT_EQ(Colmap(MatcherArgs(link), &output), 0) << output;
  EXPECT_TRUE(fs::is_symlink(link));
  ExpectCompleteDatabase(Path("real/database.db"), *reference_pairs_);
}

TEST_F(DatabaseSafety, SecondRunOnTheSameDatabaseIsRefused) {
  const std::string database = CopyOfBase("concurrent.db");
  Job first(MatcherArgs(database),
            Path("concurrent_first.log"),
            "COLMAP_GCN_STOP_AT=matching");
  ASSERT_TRUE(first.WaitFor([&] { return first.State() == 'T'; }));
  std::string output;
  EXPECT_EQ(Colmap(MatcherArgs(database), &output), 1);
  EXPECT_EQ(StringSplit(StringTrim(output), "\n").size(), 1u) << output;
  EXPECT_NE(output.find("ERROR: another gcn_matcher is using " + database +
                        " (pid " + std::to_string(first.Pid()) + ")"),
            std::string::npos)
      << output;
  first.SignalGroup(SIGCONT);
  const int status = first.Wait();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
      << ReadTextFile(Path("concurrent_first.log"));
  ExpectCompleteDatabase(database, *reference_pairs_);
}

// Every pairing leaves the database as COLMAP would: no empty "-wal" or
// "-shm" of our reads beside it, also when nothing needed matching.
TEST_F(DatabaseSafety, NoSqliteSideFilesAfterAnyPairing) {
  for (const std::string pairing : {"gcn", "knn", "exhaustive"}) {
    const std::string database = CopyOfBase("side_files_" + pairing + ".db");
    for (int run = 0; run < 2; ++run) {
      std::string output;
      ASSERT_EQ(Colmap(MatcherArgs(database,
                                   "--GcnMatching.pairing " + pairing +
                                       " --GcnMatching.k 3"),
                       &output),
                0)
          << output;
      EXPECT_FALSE(fs::exists(database + "-wal")) << pairing << " " << run;
      EXPECT_FALSE(fs::exists(database + "-shm")) << pairing << " " << run;
      EXPECT_FALSE(fs::exists(database + ".gcn-partial")) << pairing;
    }
  }
}

TEST_F(DatabaseSafety, ReadOnlyDatabaseIsRefusedUpFront) {
  const std::string database = CopyOfBase("read_only.db");
  chmod(database.c_str(), 0444);
  const std::string before = ReadTextFile(database);
  std::string output;
  EXPECT_EQ(Colmap(MatcherArgs(database), &output), 1);
  EXPECT_EQ(StringSplit(StringTrim(output), "\n").size(), 1u) << output;
  EXPECT_NE(output.find("is read-only (mode 0444)"), std::string::npos)
      << output;
  EXPECT_EQ(ReadTextFile(database), before);
  EXPECT_FALSE(fs::exists(database + ".gcn-partial"));
}

// Kills gcn_matcher and its COLMAP child (the whole process group, as a
// terminal's Ctrl-C or a killed job does) at one point of a run, then runs
// again without interruption.
struct Interruption {
  int signal_number;
  const char* point;  // pairing | matching | commit
};

class InterruptedRun : public DatabaseSafety,
                       public testing::WithParamInterface<Interruption> {};

TEST_P(InterruptedRun, ResumesToTheUninterruptedPairs) {
  const Interruption interruption = GetParam();
  const std::string point = interruption.point;
  const std::string name = "interrupted_" + point + "_" +
                           std::to_string(interruption.signal_number) + ".db";
  const std::string database = CopyOfBase(name);
  const std::string copy = database + ".gcn-partial";
  const std::string log = database + ".log";
  // Mid-matching, small blocks keep most of the run ahead of the signal.
  const int block_size = point == "matching" ? 2 : kBlockSize;
  Job job(MatcherArgs(database, "--GcnMatching.pairing exhaustive", block_size),
          log,
          point == "matching" ? "" : "COLMAP_GCN_STOP_AT=" + point);
  if (point == "matching") {
    // COLMAP is running a later block while the first one is committed.
    ASSERT_TRUE(job.WaitFor([&] {
      return job.HasChild() && fs::exists(copy) &&
             QuerySqlInt(copy, "SELECT COUNT(*) FROM two_view_geometries;") >=
                 block_size;
    })) << ReadTextFile(log);
  } else {
    ASSERT_TRUE(job.WaitFor([&] { return job.State() == 'T'; }))
        << ReadTextFile(log);
  }
  job.SignalGroup(interruption.signal_number);
  job.SignalGroup(SIGCONT);
  const int status = job.Wait();
  EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  if (point == "matching" && interruption.signal_number != SIGKILL) {
    // Wherever the signal lands in the block loop (COLMAP running, or
    // between two blocks), the run ends the same way: one ERROR line naming
    // the interruption and the shell's exit code for the signal.
    const std::string run_log = ReadTextFile(log);
    EXPECT_TRUE(WIFEXITED(status) &&
                WEXITSTATUS(status) == 128 + interruption.signal_number)
        << run_log;
    EXPECT_NE(run_log.find("ERROR: interrupted (signal " +
                           std::to_string(interruption.signal_number) + ")"),
              std::string::npos)
        << run_log;
  }
  // Never half-written: the database is as before, or complete when the
  // signal came after the rename had started (it is held until done).
  const int64_t num_after = NumGeometries(database);
  // Last: the sqlite3 shell, a read-write connection, removes the empty
  // "-wal"/"-shm" that the read above left, as a user's database would be.
  EXPECT_EQ(IntegrityCheck(database), "ok");
  EXPECT_TRUE(num_after == 0 || num_after == kNumPairs) << num_after;
  if (point == "commit") {
    EXPECT_EQ(num_after, interruption.signal_number == SIGKILL ? 0 : kNumPairs);
  }

  std::string output;
  ASSERT_EQ(Colmap(MatcherArgs(database), &output), 0) << output;
  if (point == "matching") {
    // The committed blocks were kept, not matched again.
    const size_t at = output.find("resuming the interrupted matching");
    ASSERT_NE(at, std::string::npos) << output;
    const size_t open = output.find('(', at);
    EXPECT_GE(std::stoi(output.substr(open + 1)), block_size) << output;
    EXPECT_LT(std::stoi(output.substr(open + 1)), kNumPairs) << output;
  }
  ExpectCompleteDatabase(database, *reference_pairs_);
}

std::string InterruptionName(const testing::TestParamInfo<Interruption>& info) {
  const int signal_number = info.param.signal_number;
  const std::string name = signal_number == SIGINT    ? "Sigint"
                           : signal_number == SIGTERM ? "Sigterm"
                                                      : "Sigkill";
  return name + "At_" + info.param.point;
}

INSTANTIATE_TEST_SUITE_P(AllSignalsAndPoints,
                         InterruptedRun,
                         testing::Values(Interruption{SIGINT, "pairing"},
                                         Interruption{SIGTERM, "pairing"},
                                         Interruption{SIGKILL, "pairing"},
                                         Interruption{SIGINT, "matching"},
                                         Interruption{SIGTERM, "matching"},
                                         Interruption{SIGKILL, "matching"},
                                         Interruption{SIGINT, "commit"},
                                         Interruption{SIGTERM, "commit"},
                                         Interruption{SIGKILL, "commit"}),
                         InterruptionName);

}  // namespace
}  // namespace colmap_gcn
