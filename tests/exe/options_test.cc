// Options the COLMAP way, through the built `colmap` front end: a
// --project_path ini file under the command line, COLMAP's own options
// checked by COLMAP before anything runs, and gcn_pair_exporter's hloc pairs.

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "frontend_command.h"
#include "retrieval_test_utils.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

using test::CommandResult;
using test::ExpectOneLineError;
using test::RealColmapExe;
using test::RunColmap;

class Options : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::make_unique<TemporaryDirectory>("colmap_gcn_options");
    database_path_ = Path("database.db");
    test::CreateRandomDescriptorDatabase(database_path_, 4, 40, 4, 30);
    database_before_ = ReadTextFile(database_path_);
  }

  std::string Path(const std::string& name) const {
    return JoinPaths(dir_->Path(), name);
  }

  std::string Ini(const std::string& name, const std::string& text) const {
    WriteFileAtomically(Path(name), text);
    return ShellQuote(Path(name));
  }

  std::unique_ptr<TemporaryDirectory> dir_;
  std::string database_path_;
  std::string database_before_;
};

// Every option from the file; the command line wins over it.
TEST_F(Options, ProjectFileGivesOptionsAndTheCommandLineWins) {
  const std::string ini = Ini("export.ini",
                              "database_path=" + database_path_ +
                                  "\n"
                                  "output_path=" +
                                  Path("from_file.txt") +
                                  "\n"
                                  "output_format=colmap\n"
                                  "[GcnMatching]\n"
                                  "pairing=exhaustive\n");
  const CommandResult result = RunColmap("gcn_pair_exporter --project_path " +
                                         ini + " --output_format hloc");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::vector<std::string> lines =
      StringSplit(StringTrim(ReadTextFile(Path("from_file.txt"))), "\n");
  ASSERT_EQ(lines.size(), 6u);  // exhaustive on 4 images
  for (const std::string& line : lines) {
    EXPECT_EQ(StringSplit(line, " ").size(), 2u) << line;  // hloc's layout
  }
}

TEST_F(Options, ProjectFileUnknownKeyIsOneLineBeforeAnyWork) {
  const std::string ini =
      Ini("bad.ini", "[GcnMatching]\npairing=exhaustive\nk_one=3\n");
  ExpectOneLineError(
      RunColmap("gcn_matcher --database_path " + ShellQuote(database_path_) +
                " --project_path " + ini),
      {"bad.ini:3: unknown option GcnMatching.k_one", "colmap gcn_matcher -h"});
  EXPECT_EQ(ReadTextFile(database_path_), database_before_);
  EXPECT_FALSE(ExistsFile(database_path_ + ".pairs.txt"));
}

TEST_F(Options, PairExporterRefusesAdaptivePairing) {
  ExpectOneLineError(RunColmap("gcn_pair_exporter --database_path " +
                               ShellQuote(database_path_) + " --output_path " +
                               ShellQuote(Path("pairs.txt")) +
                               " --GcnMatching.pairing adaptive"),
                     {"--GcnMatching.pairing adaptive", "gcn_matcher"});
  EXPECT_FALSE(ExistsFile(Path("pairs.txt")));
}

// A misspelt COLMAP option fails before feature extraction: no workspace.
TEST_F(Options, ReconstructorMisspeltColmapOptionFailsFirst) {
  if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
  const std::string images = Path("images");
  CreateDirIfNotExists(images);
  WriteFileAtomically(JoinPaths(images, "a.jpg"), "not an image");
  const std::string workspace = Path("workspace");
  const std::string run = "gcn_reconstructor --image_path " +
                          ShellQuote(images) + " --workspace_path " +
                          ShellQuote(workspace);
  ExpectOneLineError(RunColmap(run + " --SiftExtraction.max_num_featurez 5"),
                     {"COLMAP's feature_extractor rejects its options",
                      "--SiftExtraction.max_num_featurez"});
  ExpectOneLineError(RunColmap(run + " --Mapper.ba_refine_focal_length x"),
                     {"COLMAP's mapper rejects its options",
                      "--Mapper.ba_refine_focal_length"});
  // The same from a project file.
  const std::string ini = Ini("sift.ini", "[SiftMatching]\nmax_ratioo=0.7\n");
  ExpectOneLineError(RunColmap(run + " --project_path " + ini),
                     {"COLMAP's matches_importer rejects its options",
                      "--SiftMatching.max_ratioo"});
  EXPECT_FALSE(ExistsDir(workspace));
}

TEST_F(Options, MatcherMisspeltSiftMatchingOptionLeavesTheDatabase) {
  if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
  ExpectOneLineError(
      RunColmap(
          "gcn_matcher --database_path " + ShellQuote(database_path_) +
          " --GcnMatching.pairing exhaustive --SiftMatching.max_ratioo 1"),
      {"COLMAP's matches_importer rejects its options",
       "--SiftMatching.max_ratioo"});
  EXPECT_EQ(ReadTextFile(database_path_), database_before_);
  EXPECT_FALSE(ExistsFile(database_path_ + ".pairs.txt"));
}

}  // namespace
}  // namespace colmap_gcn
