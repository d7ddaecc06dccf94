#include "controllers/colmap_runner.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "fake_colmap.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"

namespace colmap_gcn {
namespace {

using test::ExpectErrorContaining;

TEST(HeadlessArguments, AddsCpuFlagsUnlessGiven) {
  EXPECT_EQ(HeadlessArguments("feature_extractor", {}),
            (std::vector<std::string>{"--SiftExtraction.use_gpu", "0"}));
  EXPECT_EQ(HeadlessArguments("matches_importer", {}),
            (std::vector<std::string>{"--SiftMatching.use_gpu", "0"}));
  EXPECT_EQ(HeadlessArguments("exhaustive_matcher", {}),
            (std::vector<std::string>{"--SiftMatching.use_gpu", "0"}));
  EXPECT_TRUE(
      HeadlessArguments("matches_importer", {"--SiftMatching.use_gpu=1"})
          .empty());
  EXPECT_TRUE(HeadlessArguments("mapper", {}).empty());
}

TEST(RunProcess, CapturesOutputLinesAndExitCodes) {
  std::string output;
  std::vector<std::string> lines;
  EXPECT_EQ(RunProcess("/bin/sh",
                       {"-c", "echo one; echo two >&2; exit 3"},
                       &output,
                       [&](const std::string& line) { lines.push_back(line); }),
            3);
  EXPECT_EQ(lines, (std::vector<std::string>{"one", "two"}));
  // A crash is reported like a shell does: 128 + signal.
  EXPECT_EQ(RunProcess("/bin/sh", {"-c", "kill -ABRT $$"}, &output), 134);
  EXPECT_THROW(RunProcess("/nonexistent/program", {}, &output), Error);
}

TEST(DiagnoseColmapOutput, NamesTheCauseOfTheFirstFailure) {
  EXPECT_EQ(DiagnoseColmapOutput("Processed file [1/2]\nElapsed time: 0.1"),
            "");
  EXPECT_EQ(DiagnoseColmapOutput(
                "Matching block [1/1]\n"
                "SQLite error [/colmap/src/base/database.cc, line 1092]: "
                "database or disk is full\n"
                "SQLite error [/colmap/src/base/database.cc, line 1093]: "
                "cannot commit - no transaction is active\n"),
            "the disk is full (SQLite: database or disk is full)");
  EXPECT_EQ(DiagnoseColmapOutput("SQLite error: disk I/O error"),
            "a disk I/O error (SQLite: disk I/O error)");
  EXPECT_EQ(DiagnoseColmapOutput("SQLite error [x, line 1]: no such table"),
            "a database error (SQLite: no such table)");
  EXPECT_EQ(DiagnoseColmapOutput("F1203 01:02:03.000 1 reconstruction.cc:10] "
                                 "Check failed: existing_image_id "),
            "COLMAP's own check failed (Check failed: existing_image_id)");
  EXPECT_EQ(
      DiagnoseColmapOutput("terminate called after throwing an instance of "
                           "'std::out_of_range'\n  what():  _Map_base::at\n"),
      "COLMAP aborted on an uncaught std::out_of_range: _Map_base::at");
}

TEST(ColmapRunner, FailureReportedBehindExitZeroIsAnError) {
  TemporaryDirectory dir;
  const test::FakeColmap fake(dir.Path());
  fake.PrintOnEveryRun("SQLite error [db.cc, line 9]: disk I/O error\n");
  ExpectErrorContaining(
      [&] { fake.Runner().Run("mapper", {}); },
      "colmap mapper reported a disk I/O error (SQLite: disk I/O error) "
      "although it exited 0");
  fake.FailRuns();
  ExpectErrorContaining([&] { fake.Runner().Run("mapper", {}); },
                        "colmap mapper failed (exit 1): ");
}

TEST(ParseColmapProgress, ReadsTheCountsOfColmapsProgressLines) {
  ColmapProgress progress;
  ASSERT_TRUE(ParseColmapProgress("Processed file [17/24]", &progress));
  EXPECT_EQ(progress.label, "extracting features");
  EXPECT_EQ(progress.unit, "images");
  EXPECT_EQ(progress.done, 17u);
  EXPECT_EQ(progress.total, 24u);
  // Exhaustive matching numbers the blocks of an n x m grid.
  ASSERT_TRUE(ParseColmapProgress("Matching block [2/3, 1/3]", &progress));
  EXPECT_EQ(progress.label, "matching");
  EXPECT_EQ(progress.unit, "blocks");
  EXPECT_EQ(progress.done, 4u);
  EXPECT_EQ(progress.total, 9u);
  ASSERT_TRUE(ParseColmapProgress("Matching image [4/24]", &progress));
  EXPECT_EQ(progress.unit, "images");
  // The mapper counts the registered images, of an unknown total.
  ASSERT_TRUE(ParseColmapProgress("Registering image #12 (5)", &progress));
  EXPECT_EQ(progress.label, "registering");
  EXPECT_EQ(progress.done, 5u);
  EXPECT_EQ(progress.total, 0u);
  EXPECT_FALSE(ParseColmapProgress("  Features:        10", &progress));
  // matches_importer's one block per run, printed at its end.
  EXPECT_FALSE(ParseColmapProgress("Matching block [1/1] in 8.5s", &progress));
  EXPECT_FALSE(ParseColmapProgress("Elapsed time: 0.1 [minutes]", &progress));
}

// Captures what the library logs.
class CapturingSink : public LogSink {
 public:
  void Send(LogLevel, const std::string& message) override {
    messages.push_back(message);
  }
  std::vector<std::string> messages;
};

TEST(ColmapRunner, SummarisesColmapsProgressUnlessVerbose) {
  TemporaryDirectory dir;
  const test::FakeColmap fake(dir.Path());
  // A command the fake does nothing for, printing feature_extractor's lines.
  fake.PrintOnEveryRun(
      "Processed file [1/2]\n  Features: 10\nProcessed file [2/2]\n"
      "  Features: 12\nElapsed time: 0.001 [minutes]\n");
  ColmapRunnerOptions options;
  options.colmap_exe = fake.Runner().Executable();
  options.log_path = JoinPaths(dir.Path(), "colmap.log");
  {
    CapturingSink sink;
    const ScopedLogSink scoped(&sink);
    ColmapRunner(options).Run("model_analyzer", {});
    // COLMAP's lines go only to the log file; a step this quick is not
    // even summarised (ProgressLogger::kQuietSeconds).
    EXPECT_TRUE(sink.messages.empty()) << sink.messages[0];
  }
  EXPECT_NE(ReadTextFile(options.log_path).find("Features: 12"),
            std::string::npos);
  options.verbose = true;
  CapturingSink sink;
  const ScopedLogSink scoped(&sink);
  ColmapRunner(options).Run("model_analyzer", {});
  EXPECT_EQ(sink.messages.size(), 5u);
  EXPECT_EQ(sink.messages[1], "[colmap model_analyzer]   Features: 10");
}

TEST(FindColmapExecutable, HonoursHintAndRejectsMissing) {
  EXPECT_THROW(FindColmapExecutable("/nonexistent/colmap"), Error);
  const std::string real = test::RealColmapExe();
  if (real.empty()) GTEST_SKIP() << "COLMAP not installed";
  EXPECT_EQ(FindColmapExecutable(real), real);
}

TEST(ColmapRunner, ReportsVersionAndFailures) {
  if (test::RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
  ColmapRunnerOptions options;
  options.colmap_exe = test::RealColmapExe();
  options.show_progress = false;
  TemporaryDirectory dir;
  options.log_path = JoinPaths(dir.Path(), "colmap.log");
  const ColmapRunner colmap(options);
  EXPECT_EQ(colmap.Version().substr(0, 2), "3.");
  try {
    colmap.Run("model_analyzer", {"--path", JoinPaths(dir.Path(), "none")});
    FAIL() << "expected an error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("model_analyzer"), std::string::npos);
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_NE(ReadTextFile(options.log_path).find("model_analyzer"),
            std::string::npos);
}

TEST(ColmapRunner, RejectsAProgramThatIsNotColmap) {
  ColmapRunnerOptions options;
  options.colmap_exe = "/bin/true";
  EXPECT_THROW(ColmapRunner runner(options), Error);
}

// COLMAP itself parses the options meant for it, before anything runs.
TEST(CheckColmapArguments, ColmapRejectsMisspeltAndMalformedOptions) {
  if (test::RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
  CheckColmapArguments({"--SiftExtraction.max_num_features",
                        "2048",
                        "--ImageReader.camera_model",
                        "PINHOLE",
                        "--SiftMatching.max_ratio=0.7",
                        "--Mapper.ba_refine_focal_length",
                        "0"});
  ExpectErrorContaining(
      [] {
        CheckColmapArguments({"--SiftExtraction.max_num_featurez", "5"});
      },
      "COLMAP's feature_extractor rejects its options: unrecognised option "
      "'--SiftExtraction.max_num_featurez'");
  ExpectErrorContaining(
      [] {
        CheckColmapArguments({"--SiftMatching.max_ratio", "abc"});
      },
      "COLMAP's matches_importer rejects its options");
  ExpectErrorContaining(
      [] { CheckColmapArguments({"--Mapper.no_such_option=1"}); },
      "COLMAP's mapper rejects its options: unrecognised option "
      "'--Mapper.no_such_option");
}

// Nothing for COLMAP: COLMAP is not even looked for.
TEST(CheckColmapArguments, NoColmapOptionsNeedNoColmap) {
  CheckColmapArguments({}, "/nonexistent/colmap");
}

}  // namespace
}  // namespace colmap_gcn
