// Every command's answer to bad input, through the built `colmap` front end
// as users run it: exit code 1, stderr exactly one "ERROR: " line naming the
// option (or file) and the offending value, nothing done before the check.
// Only the cases that must run COLMAP to fail skip without it.

#include <filesystem>

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "frontend_command.h"
#include "retrieval/vlad.h"
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
using test::RunShell;

// A small valid database (3 images with descriptors) per test.
class BadInput : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::make_unique<TemporaryDirectory>("colmap_gcn_bad_input");
    database_path_ = JoinPaths(dir_->Path(), "database.db");
    test::CreateRandomDescriptorDatabase(database_path_, 3, 40, 4, 10);
    database_before_ = ReadTextFile(database_path_);
  }

  std::string Path(const std::string& name) const {
    return JoinPaths(dir_->Path(), name);
  }

  // gcn_matcher on the valid database with extra arguments; the database
  // must be left as it was and no pairs file written.
  void ExpectMatcherError(const std::string& args,
                          const std::vector<std::string>& needles) {
    ExpectOneLineError(RunColmap("gcn_matcher --database_path " +
                                 ShellQuote(database_path_) + " " + args),
                       needles);
    EXPECT_EQ(ReadTextFile(database_path_), database_before_);
    EXPECT_FALSE(ExistsFile(database_path_ + ".pairs.txt"));
  }

  // gcn_benchmark with the given arguments; the output folder must not
  // even be created (every check runs before any work).
  void ExpectBenchmarkError(const std::string& args,
                            const std::vector<std::string>& needles) {
    const std::string out = Path("benchmark_out");
    ExpectOneLineError(RunColmap("gcn_benchmark --output_path " +
                                 ShellQuote(out) + " " + args),
                       needles);
    EXPECT_FALSE(ExistsDir(out));
  }

  std::unique_ptr<TemporaryDirectory> dir_;
  std::string database_path_;
  std::string database_before_;
};

// --- gcn_matcher: the "-1 = the model's value" options ---------------------

TEST_F(BadInput, MatcherK1Zero) {
  ExpectMatcherError(
      "--GcnMatching.k1 0",
      {"--GcnMatching.k1 must be -1 (the model's value) or >= 1 (got 0)"});
}

TEST_F(BadInput, MatcherK1Negative) {
  ExpectMatcherError("--GcnMatching.k1 -3",
                     {"--GcnMatching.k1", ">= 1", "(got -3)"});
}

TEST_F(BadInput, MatcherK1NotAnInteger) {
  ExpectMatcherError("--GcnMatching.k1 1.5", {"--GcnMatching.k1", "1.5"});
}

TEST_F(BadInput, MatcherK1Text) {
  ExpectMatcherError("--GcnMatching.k1 abc", {"--GcnMatching.k1", "abc"});
}

TEST_F(BadInput, MatcherK2Zero) {
  ExpectMatcherError("--GcnMatching.k2 0",
                     {"--GcnMatching.k2 must be -1", ">= 1 (got 0)"});
}

TEST_F(BadInput, MatcherUZero) {
  ExpectMatcherError("--GcnMatching.u 0",
                     {"--GcnMatching.u must be -1", ">= 1 (got 0)"});
}

TEST_F(BadInput, MatcherThresholdAboveOne) {
  ExpectMatcherError("--GcnMatching.threshold 1.5",
                     {"--GcnMatching.threshold must be -1 (the model's "
                      "value) or in [0, 1] (got 1.5)"});
}

TEST_F(BadInput, MatcherThresholdNegative) {
  ExpectMatcherError("--GcnMatching.threshold -0.5",
                     {"--GcnMatching.threshold", "[0, 1]", "(got -0.5)"});
}

// --- gcn_matcher: other options -------------------------------------------

TEST_F(BadInput, MatcherMinPairsPerImageNegative) {
  ExpectMatcherError(
      "--GcnMatching.min_pairs_per_image -1",
      {"--GcnMatching.min_pairs_per_image must be >= 0 (got -1)"});
}

TEST_F(BadInput, MatcherNumThreadsZero) {
  ExpectMatcherError(
      "--GcnMatching.num_threads 0",
      {"--GcnMatching.num_threads must be -1 (all cores) or >= 1 (got 0)"});
}

TEST_F(BadInput, MatcherNumThreadsMinusTwo) {
  ExpectMatcherError("--GcnMatching.num_threads -2",
                     {"--GcnMatching.num_threads", "(got -2)"});
}

TEST_F(BadInput, MatcherUnknownPairing) {
  // The built-in generators first, in registration order; generators
  // registered later follow them.
  ExpectMatcherError("--GcnMatching.pairing foo",
                     {"--GcnMatching.pairing must be one of "
                      "gcn|exhaustive|imported|knn|vocab_tree",
                      "(got \"foo\")"});
}

TEST_F(BadInput, MatcherImportedWithoutPairsFile) {
  ExpectMatcherError(
      "--GcnMatching.pairing imported",
      {"--GcnMatching.match_list_path must name a pairs file", "(got \"\")"});
}

TEST_F(BadInput, MatcherKnnKZero) {
  ExpectMatcherError("--GcnMatching.pairing knn --GcnMatching.k 0",
                     {"--GcnMatching.k must be >= 1 (got 0)"});
}

TEST_F(BadInput, MatcherAdaptiveYieldAboveOne) {
  ExpectMatcherError(
      "--GcnMatching.pairing adaptive --GcnMatching.min_pair_yield 2",
      {"--GcnMatching.min_pair_yield must be in [0, 1] (got 2)"});
}

TEST_F(BadInput, MatcherGraphMatchRoundSizeZero) {
  ExpectMatcherError(
      "--GcnMatching.pairing graphmatch --GcnMatching.round_size 0",
      {"--GcnMatching.round_size must be -1", "(got 0)"});
}

TEST_F(BadInput, AdaptiveSimulatorNeedsAGeneratorThatUsesVerification) {
  ExpectOneLineError(
      RunColmap("gcn_adaptive_simulator --database_path " +
                ShellQuote(database_path_) + " --GcnMatching.pairing knn"),
      {"--GcnMatching.pairing knn", "adaptive or graphmatch"});
  ExpectOneLineError(RunColmap("gcn_adaptive_simulator --database_path " +
                               ShellQuote(database_path_) + " --labels_path " +
                               ShellQuote(Path("none.csv"))),
                     {"--labels_path", "none.csv", "does not exist"});
  EXPECT_EQ(ReadTextFile(database_path_), database_before_);
}

TEST_F(BadInput, MatcherUnknownEmbedding) {
  ExpectMatcherError("--GcnMatching.embedding sift",
                     {"--GcnMatching.embedding must be one of "
                      "default|vlad|onnx|vlad+onnx|imported (got \"sift\")"});
}

TEST_F(BadInput, MatcherOnnxNeedsNetworkAndImages) {
  ExpectMatcherError(
      "--GcnMatching.pairing knn --GcnMatching.embedding onnx",
      {"--GcnMatching.onnx_path must name the ONNX network", "(got \"\")"});
  ExpectMatcherError(
      "--GcnMatching.pairing knn --GcnMatching.embedding onnx "
      "--GcnMatching.onnx_path net.onnx",
      {"--GcnMatching.image_path must name the image folder", "(got \"\")"});
}

TEST_F(BadInput, MatcherOnnxOptions) {
  ExpectMatcherError("--GcnMatching.onnx_gem_p 0.5",
                     {"--GcnMatching.onnx_gem_p must be -1 (the model's "
                      "value) or >= 1 (got 0.5)"});
  ExpectMatcherError("--GcnMatching.onnx_swap_rb 2",
                     {"--GcnMatching.onnx_swap_rb must be -1", "(got 2)"});
  ExpectMatcherError("--GcnMatching.onnx_batch_size 0",
                     {"--GcnMatching.onnx_batch_size must be >= 1 (got 0)"});
}

TEST_F(BadInput, MatcherMinNumInliersText) {
  ExpectMatcherError(
      "--GcnMatching.pairing exhaustive "
      "--SiftMatching.min_num_inliers abc",
      {"--SiftMatching.min_num_inliers", "abc"});
}

TEST_F(BadInput, MatcherMinNumInliersNegative) {
  ExpectMatcherError("--SiftMatching.min_num_inliers=-1",
                     {"--SiftMatching.min_num_inliers must be >= 0 (got -1)"});
}

TEST_F(BadInput, MatcherLogInMissingFolder) {
  const std::string log = Path("no_such_folder/colmap.log");
  ExpectMatcherError(
      "--GcnMatching.pairing exhaustive "
      "--GcnMatching.colmap_log_path " +
          ShellQuote(log),
      {log, "does not exist"});
}

TEST_F(BadInput, MatcherPairsFileInMissingFolder) {
  const std::string pairs = Path("no_such_folder/pairs.txt");
  ExpectMatcherError(
      "--GcnMatching.pairing exhaustive "
      "--GcnMatching.pairs_path " +
          ShellQuote(pairs),
      {pairs, "does not exist"});
}

TEST_F(BadInput, MatcherUnknownOption) {
  ExpectMatcherError("--GcnMatching.nope 1", {"--GcnMatching.nope"});
}

// --- gcn_matcher: databases ------------------------------------------------

TEST_F(BadInput, MatcherDatabaseWithoutDescriptors) {
  const std::string path = Path("no_descriptors.db");
  test::CreateDescriptorDatabase(path,
                                 {{"a.jpg", FeatureDescriptors(0, 128)},
                                  {"b.jpg", FeatureDescriptors(0, 128)},
                                  {"c.jpg", FeatureDescriptors(0, 128)}});
  ASSERT_EQ(
      RunShell("sqlite3 " + ShellQuote(path) + " 'DELETE FROM descriptors;'"),
      0);
  const CommandResult result = RunColmap(
      "gcn_matcher --GcnMatching.pairing exhaustive --database_path " +
      ShellQuote(path));
  ExpectOneLineError(result, {path, "3 images but no descriptors"});
  EXPECT_FALSE(ExistsFile(path + ".pairs.txt"));
}

// A descriptor size the embedding's codebook does not have fails inside the
// embedding's worker threads: the error must reach the front end (before,
// std::terminate aborted the process with exit 134).
TEST_F(BadInput, MatcherWorkerThreadErrorIsOneLine) {
  const int kWords = 4;
  const int kDim = 64;
  FloatMatrix codebook = FloatMatrix::Ones(kWords, kDim);
  PcaWhitening pca;
  pca.mean = Eigen::RowVectorXf::Zero(kWords * kDim);
  pca.projection = FloatMatrix::Identity(8, kWords * kDim);
  pca.eigenvalues = Eigen::VectorXf::Ones(8);
  const std::string embedding_path = Path("embedding64.bin");
  VladEmbedding(codebook, pca).Write(embedding_path);
  ExpectMatcherError(
      "--GcnMatching.pairing knn --GcnMatching.k 1 "
      "--GcnMatching.num_threads 2 "
      "--GcnMatching.embedding_path " +
          ShellQuote(embedding_path),
      {"descriptors have 128 columns, the VLAD codebook 64"});
}

TEST_F(BadInput, MatcherImportedPairsFileWithoutPairs) {
  const std::string empty = Path("empty_pairs.txt");
  WriteFileAtomically(empty, "");
  ExpectMatcherError(
      "--GcnMatching.pairing imported "
      "--GcnMatching.match_list_path " +
          ShellQuote(empty),
      {empty, "lists no image pairs; nothing to match"});
  const std::string self = Path("self_pairs.txt");
  WriteFileAtomically(self, "image0.jpg image0.jpg\nimage1.jpg image1.jpg\n");
  ExpectMatcherError(
      "--GcnMatching.pairing imported --GcnMatching.match_list_path " +
          ShellQuote(self),
      {self,
       "lists only pairs of an image with itself (2 lines); nothing to "
       "match"});
}

// The files in a folder, sorted.
std::vector<std::string> FolderListing(const std::string& path) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(path)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// A run that fails after pairing but before COLMAP wrote anything has
// nothing to resume: it leaves no pairs file, embedding cache, working copy
// or SQLite side file behind, for every kind of pairing. The failure: an
// image name COLMAP's pairs file cannot hold, found when the first pairs
// are written (COLMAP itself is a stand-in that never gets to run).
TEST_F(BadInput, MatcherFailingBeforeColmapLeavesNoFiles) {
  const std::string colmap = Path("colmap");
  WriteFileAtomically(colmap, "#!/bin/sh\necho 'COLMAP 3.8 (stand-in)'\n");
  ASSERT_EQ(RunShell("chmod +x " + ShellQuote(colmap)), 0);
  const std::string path = Path("spaced_name.db");
  std::vector<std::pair<std::string, FeatureDescriptors>> images;
  for (int i = 0; i < 4; ++i) {
    images.emplace_back("image " + std::to_string(i) + ".jpg",
                        test::RandomDescriptors(40, 4, 20 + i));
  }
  test::CreateDescriptorDatabase(path, images);
  const std::string before = ReadTextFile(path);
  const std::vector<std::string> listing = FolderListing(dir_->Path());
  for (const std::string pairing : {"gcn", "knn", "exhaustive", "adaptive"}) {
    const CommandResult result = RunColmap(
        "gcn_matcher --database_path " + ShellQuote(path) +
            " --GcnMatching.pairing " + pairing + " --GcnMatching.k 2",
        "COLMAP_EXE=" + ShellQuote(colmap));
    EXPECT_EQ(result.exit_code, 1) << pairing << ": " << result.err;
    // Warnings may come first; the error is the one last line.
    const std::vector<std::string> lines =
        StringSplit(StringTrim(result.err), "\n");
    EXPECT_TRUE(StringStartsWith(lines.back(), "ERROR: image name \"image "))
        << pairing << ": " << result.err;
    EXPECT_EQ(std::count_if(lines.begin(),
                            lines.end(),
                            [](const std::string& line) {
                              return StringStartsWith(line, "ERROR:");
                            }),
              1)
        << result.err;
    EXPECT_EQ(FolderListing(dir_->Path()), listing) << pairing;
    EXPECT_EQ(ReadTextFile(path), before) << pairing;
  }
}

// --- gcn_reconstructor ------------------------------------------------------

TEST_F(BadInput, ReconstructorEmptyImageFolder) {
  const std::string images = Path("empty_images");
  CreateDirIfNotExists(images);
  const std::string workspace = Path("workspace");
  ExpectOneLineError(
      RunColmap("gcn_reconstructor --image_path " + ShellQuote(images) +
                " --workspace_path " + ShellQuote(workspace)),
      {"image folder " + images + " holds no files"});
  // COLMAP never ran: no database was created.
  EXPECT_FALSE(ExistsFile(JoinPaths(workspace, "database.db")));
}

TEST_F(BadInput, ReconstructorMissingImageFolder) {
  const std::string images = Path("no_such_images");
  ExpectOneLineError(
      RunColmap("gcn_reconstructor --image_path " + ShellQuote(images) +
                " --workspace_path " + ShellQuote(Path("workspace"))),
      {"image folder not found", images});
}

TEST_F(BadInput, ReconstructorOptionCheckedBeforeExtraction) {
  const std::string images = Path("images");
  CreateDirIfNotExists(images);
  WriteFileAtomically(JoinPaths(images, "a.jpg"), "not an image");
  const std::string workspace = Path("workspace");
  ExpectOneLineError(
      RunColmap("gcn_reconstructor --image_path " + ShellQuote(images) +
                " --workspace_path " + ShellQuote(workspace) +
                " --GcnMatching.threshold 2"),
      {"--GcnMatching.threshold", "(got 2)"});
  EXPECT_FALSE(ExistsDir(workspace));
}

TEST_F(BadInput, ReconstructorLogInMissingFolder) {
  const std::string images = Path("images");
  CreateDirIfNotExists(images);
  WriteFileAtomically(JoinPaths(images, "a.jpg"), "not an image");
  const std::string log = Path("no_such_folder/colmap.log");
  ExpectOneLineError(
      RunColmap("gcn_reconstructor --image_path " + ShellQuote(images) +
                " --workspace_path " + ShellQuote(Path("workspace")) +
                " --GcnMatching.colmap_log_path " + ShellQuote(log)),
      {log, "does not exist"});
}

// Files that are no images: COLMAP reads none of them.
TEST_F(BadInput, ReconstructorFolderWithoutReadableImages) {
  if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
  const std::string images = Path("images");
  CreateDirIfNotExists(images);
  WriteFileAtomically(JoinPaths(images, "a.jpg"), "not an image");
  WriteFileAtomically(JoinPaths(images, "b.jpg"), "not an image either");
  const CommandResult result =
      RunColmap("gcn_reconstructor --image_path " + ShellQuote(images) +
                " --workspace_path " + ShellQuote(Path("workspace")) +
                " --SiftExtraction.num_threads 1");
  EXPECT_EQ(result.exit_code, 1) << result.err;
  // COLMAP's progress comes first; the error is the last line.
  const std::vector<std::string> lines =
      StringSplit(StringTrim(result.err), "\n");
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(std::count_if(lines.begin(),
                          lines.end(),
                          [](const std::string& line) {
                            return StringStartsWith(line, "ERROR: ");
                          }),
            1)
      << result.err;
  EXPECT_TRUE(StringStartsWith(lines.back(), "ERROR: ")) << result.err;
  EXPECT_NE(lines.back().find("read 0 image(s) from " + images),
            std::string::npos)
      << result.err;
}

// --- gcn_benchmark: datasets, methods and options, all before any work -----

TEST_F(BadInput, BenchmarkMissingDatasetPath) {
  const std::string path = Path("no_such_scene");
  ExpectBenchmarkError("--datasets " + ShellQuote(path),
                       {"dataset " + path + " does not exist"});
}

TEST_F(BadInput, BenchmarkDatasetIsAGarbageFile) {
  const std::string path = Path("garbage.bin");
  WriteFileAtomically(path, "\x01\x02 garbage");
  ExpectBenchmarkError("--datasets " + ShellQuote(path),
                       {"dataset " + path + " is not a folder"});
}

TEST_F(BadInput, BenchmarkDatasetWithoutImagesFolder) {
  const std::string path = Path("scene");
  CreateDirIfNotExists(path);
  ExpectBenchmarkError("--datasets " + ShellQuote(path),
                       {"dataset " + path + " has no images/ folder"});
}

TEST_F(BadInput, BenchmarkDatasetWithOneImage) {
  const std::string path = Path("scene");
  CreateDirIfNotExists(JoinPaths(path, "images"));
  WriteFileAtomically(JoinPaths(path, "images/a.jpg"), "x");
  ExpectBenchmarkError("--datasets " + ShellQuote(path),
                       {"dataset " + path + " has 1 image(s)", "need >= 2"});
}

TEST_F(BadInput, BenchmarkListTxtNamesMissingImages) {
  const std::string path = Path("scene");
  CreateDirIfNotExists(JoinPaths(path, "images"));
  WriteFileAtomically(JoinPaths(path, "images/a.jpg"), "x");
  WriteFileAtomically(JoinPaths(path, "list.txt"),
                      "images/a.jpg\nimages/missing.jpg 0 500\n");
  WriteFileAtomically(JoinPaths(path, "bundle.out"),
                      "# Bundle file v0.3\n2 0\n");
  ExpectBenchmarkError(
      "--datasets " + ShellQuote(path),
      {"1 of the 2 images in list.txt do not exist", "images/missing.jpg"});
}

TEST_F(BadInput, BenchmarkGarbageBundleFile) {
  const std::string path = Path("scene");
  CreateDirIfNotExists(JoinPaths(path, "images"));
  WriteFileAtomically(JoinPaths(path, "images/a.jpg"), "x");
  WriteFileAtomically(JoinPaths(path, "images/b.jpg"), "x");
  WriteFileAtomically(JoinPaths(path, "list.txt"),
                      "images/a.jpg\nimages/b.jpg\n");
  WriteFileAtomically(JoinPaths(path, "bundle.out"), "garbage garbage\n");
  ExpectBenchmarkError("--datasets " + ShellQuote(path),
                       {JoinPaths(path, "bundle.out"), "not a Bundler file"});
}

TEST_F(BadInput, BenchmarkUnknownSyntheticFamily) {
  ExpectBenchmarkError(
      "--datasets synth:gothic:10",
      {"dataset \"synth:gothic:10\"",
       "family must be one of ordinary|repetitive|symmetric|twin_print|"
       "twin_objects (got "
       "\"gothic\")"});
}

TEST_F(BadInput, BenchmarkSyntheticSceneOfOneImage) {
  ExpectBenchmarkError("--datasets synth:ordinary:1",
                       {"num_images must be in [2, 100000] (got 1)"});
}

TEST_F(BadInput, BenchmarkMalformedSyntheticSpec) {
  ExpectBenchmarkError("--datasets synth:ordinary:ten",
                       {"synth:ordinary:ten", "numbers expected"});
}

TEST_F(BadInput, BenchmarkEveryBadDatasetNamed) {
  const std::string path = Path("no_such_scene");
  ExpectBenchmarkError(
      "--datasets " + ShellQuote(path) + ",synth:gothic:10",
      {path + " does not exist", "synth:gothic:10", "\"gothic\""});
}

TEST_F(BadInput, BenchmarkUnknownMethod) {
  ExpectBenchmarkError(
      "--datasets synth:ordinary:10 --methods exhaustive,bogus",
      {"bad method \"bogus\" in --methods",
       "exhaustive|knn:<k>|vocab_tree:<k>|",
       "|gcn|oracle"});
}

TEST_F(BadInput, BenchmarkMethodKZero) {
  ExpectBenchmarkError("--datasets synth:ordinary:10 --methods knn:0",
                       {"bad k in method \"knn:0\"", ">= 1"});
}

TEST_F(BadInput, BenchmarkTauMoAboveOne) {
  ExpectBenchmarkError("--datasets synth:ordinary:10 --Benchmark.tau_mo 1.5",
                       {"--Benchmark.tau_mo must be in (0, 1] (got 1.5)"});
}

TEST_F(BadInput, BenchmarkMapperThreadsZero) {
  ExpectBenchmarkError(
      "--datasets synth:ordinary:10 --Benchmark.mapper_num_threads 0",
      {"--Benchmark.mapper_num_threads must be -1 (all cores) or >= 1 "
       "(got 0)"});
}

TEST_F(BadInput, BenchmarkGcnMatchingOptionChecked) {
  ExpectBenchmarkError("--datasets synth:ordinary:10 --GcnMatching.k1 0",
                       {"--GcnMatching.k1 must be -1", "(got 0)"});
}

TEST_F(BadInput, BenchmarkPairingSetByMethods) {
  ExpectBenchmarkError("--datasets synth:ordinary:10 --GcnMatching.pairing knn",
                       {"--GcnMatching.pairing must not be given to "
                        "gcn_benchmark (each --methods entry sets it) (got "
                        "\"knn\")"});
}

TEST_F(BadInput, BenchmarkKSetByMethods) {
  ExpectBenchmarkError("--datasets synth:ordinary:10 --GcnMatching.k=5",
                       {"--GcnMatching.k must not be given", "(got \"5\")"});
}

TEST_F(BadInput, BenchmarkMinNumInliersText) {
  ExpectBenchmarkError(
      "--datasets synth:ordinary:10 --SiftMatching.min_num_inliers abc",
      {"--SiftMatching.min_num_inliers", "abc"});
}

// A scene that passes the checks but fails while running (its two "images"
// cannot be decoded): the run's exit code says so, and the summary names the
// scene; --Benchmark.keep_going 1 exits 0 with the same summary.
TEST_F(BadInput, BenchmarkFailedSceneExitsOneUnlessKeepGoing) {
  if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
  const std::string path = Path("broken");
  CreateDirIfNotExists(JoinPaths(path, "images"));
  WriteFileAtomically(JoinPaths(path, "images/a.jpg"), "not an image");
  WriteFileAtomically(JoinPaths(path, "images/b.jpg"), "not an image either");
  const std::string args = "gcn_benchmark --datasets " + ShellQuote(path) +
                           " --methods exhaustive --SiftExtraction.num_threads "
                           "1 --output_path ";
  const CommandResult failed = RunColmap(args + ShellQuote(Path("out1")));
  EXPECT_EQ(failed.exit_code, 1) << failed.err;
  const std::vector<std::string> lines =
      StringSplit(StringTrim(failed.err), "\n");
  ASSERT_FALSE(lines.empty());
  EXPECT_TRUE(StringStartsWith(lines.back(),
                               "ERROR: gcn_benchmark: 1 "
                               "failure(s) in 1 scene(s)"))
      << failed.err;
  EXPECT_NE(failed.err.find("[gcn_benchmark]   broken: "), std::string::npos)
      << failed.err;

  const CommandResult kept =
      RunColmap(args + ShellQuote(Path("out2")) + " --Benchmark.keep_going 1");
  EXPECT_EQ(kept.exit_code, 0) << kept.err;
  EXPECT_NE(kept.err.find("[gcn_benchmark]   broken: "), std::string::npos)
      << kept.err;
  EXPECT_EQ(kept.err.find("ERROR: "), std::string::npos) << kept.err;
}

// --- gcn_synth
// ----------------------------------------------------------------

TEST_F(BadInput, SynthUnknownFamily) {
  ExpectOneLineError(
      RunColmap("gcn_synth --output_path " + ShellQuote(Path("synth")) +
                " --GcnSynth.family gothic"),
      {"--GcnSynth.family must be one of "
       "ordinary|repetitive|symmetric|twin_print|twin_objects (got "
       "\"gothic\")"});
  EXPECT_FALSE(ExistsDir(Path("synth")));
}

TEST_F(BadInput, SynthOneImage) {
  ExpectOneLineError(
      RunColmap("gcn_synth --output_path " + ShellQuote(Path("synth")) +
                " --GcnSynth.num_images 1"),
      {"--GcnSynth.num_images must be in [2, 100000] (got 1)"});
}

TEST_F(BadInput, SynthNumThreadsZero) {
  ExpectOneLineError(
      RunColmap("gcn_synth --output_path " + ShellQuote(Path("synth")) +
                " --GcnSynth.num_threads 0"),
      {"--GcnSynth.num_threads must be -1 (all cores) or >= 1 (got 0)"});
}

// --- gcn_train: checked before any scene is read -----------------------------

class BadTrainInput : public BadInput {
 protected:
  void ExpectTrainError(const std::string& args,
                        const std::vector<std::string>& needles) {
    ExpectOneLineError(
        RunColmap("gcn_train --benchmark_path " +
                  ShellQuote(Path("no_such_benchmark")) + " --output_path " +
                  ShellQuote(Path("model.bin")) + " " + args),
        needles);
    EXPECT_FALSE(ExistsFile(Path("model.bin")));
  }
};

TEST_F(BadTrainInput, UnknownOptimizer) {
  ExpectTrainError("--GcnTraining.optimizer rmsprop",
                   {"--GcnTraining.optimizer must be one of sgd|adam (got "
                    "\"rmsprop\")"});
}

TEST_F(BadTrainInput, UnknownAggregation) {
  ExpectTrainError("--GcnTraining.aggregation mean",
                   {"--GcnTraining.aggregation must be one of symmetric|row "
                    "(got \"mean\")"});
}

TEST_F(BadTrainInput, UnknownFeatureScaling) {
  ExpectTrainError("--GcnTraining.feature_scaling global",
                   {"--GcnTraining.feature_scaling must be one of none|query "
                    "(got \"global\")"});
}

TEST_F(BadTrainInput, UnknownStructureFeatures) {
  ExpectTrainError("--GcnTraining.structure_features rank",
                   {"--GcnTraining.structure_features must be one of "
                    "none|reciprocal|reciprocal_only (got \"rank\")"});
}

TEST_F(BadTrainInput, DistancePriorNeedsEmbeddingDifferences) {
  ExpectTrainError(
      "--GcnTraining.initialization distance_prior "
      "--GcnTraining.structure_features reciprocal_only",
      {"--GcnTraining.structure_features must keep the embedding "
       "differences with the distance prior (got "
       "reciprocal_only)"});
}

TEST_F(BadTrainInput, UnknownInitialization) {
  ExpectTrainError("--GcnTraining.initialization zeros",
                   {"--GcnTraining.initialization must be one of "
                    "xavier|distance_prior (got \"zeros\")"});
}

TEST_F(BadTrainInput, UnknownEmbedding) {
  ExpectTrainError("--GcnTraining.embedding sift",
                   {"--GcnTraining.embedding must be one of "
                    "vlad|onnx|vlad+onnx (got \"sift\")"});
}

TEST_F(BadTrainInput, OnnxNeedsNetworkAndImageRoot) {
  ExpectTrainError("--GcnTraining.embedding onnx",
                   {"--GcnTraining.onnx_path must name the ONNX network when "
                    "the embedding is onnx (got \"\")"});
  ExpectTrainError(
      "--GcnTraining.embedding onnx --GcnTraining.onnx_path net.onnx "
      "--image_root " +
          ShellQuote(Path("no_such_images")),
      {"--image_root must be a folder with one subfolder <scene>/images"});
  ExpectTrainError("--GcnTraining.onnx_max_image_size 16",
                   {"--GcnTraining.onnx_max_image_size must be >= 32 (got "
                    "16)"});
}

TEST_F(BadTrainInput, ZeroLayerSize) {
  ExpectTrainError("--GcnTraining.gcn_dims 512,0",
                   {"--GcnTraining.gcn_dims must be a comma list of positive "
                    "sizes (got \"512,0\")"});
}

TEST_F(BadTrainInput, K1Zero) {
  ExpectTrainError("--GcnTraining.k1 0",
                   {"--GcnTraining.k1 must be >= 1 (got 0)"});
}

TEST_F(BadTrainInput, TestUNegative) {
  ExpectTrainError("--GcnTraining.test_u -1",
                   {"--GcnTraining.test_u must be >= 0 (got -1)"});
}

TEST_F(BadTrainInput, ThresholdOne) {
  ExpectTrainError(
      "--GcnTraining.threshold 1",
      {"--GcnTraining.threshold must be < 0", "(0, 1)", "(got 1)"});
}

TEST_F(BadTrainInput, NumThreadsZero) {
  ExpectTrainError("--GcnTraining.num_threads 0",
                   {"--GcnTraining.num_threads must be -1 (all cores) or >= 1 "
                    "(got 0)"});
}

TEST_F(BadTrainInput, LearningRateZero) {
  ExpectTrainError("--GcnTraining.learning_rate 0",
                   {"--GcnTraining.learning_rate must be > 0 (got 0)"});
}

TEST_F(BadTrainInput, TauMoZero) {
  ExpectTrainError("--GcnTraining.tau_mo 0",
                   {"--GcnTraining.tau_mo must be in (0, 1] (got 0)"});
}

TEST_F(BadTrainInput, VladWordsZero) {
  ExpectTrainError("--Vlad.num_words 0",
                   {"--Vlad.num_words must be >= 1 (got 0)"});
}

// --- gcn_model_evaluator, gcn_embedding_trainer, gcn_vocab_tree_builder ----

TEST_F(BadInput, ModelEvaluatorMaxKZero) {
  ExpectOneLineError(RunColmap("gcn_model_evaluator --benchmark_path " +
                               ShellQuote(Path("none")) + " --max_k 0"),
                     {"--max_k must be >= 1 (got 0)"});
}

TEST_F(BadInput, ModelEvaluatorTauMoAboveOne) {
  ExpectOneLineError(
      RunColmap("gcn_model_evaluator --benchmark_path " +
                ShellQuote(Path("none")) + " --tau_mo 1.5"),
      {"--tau_mo must be < 0 (the model's value) or in (0, 1] (got 1.5)"});
}

TEST_F(BadInput, ModelEvaluatorNumThreadsZero) {
  ExpectOneLineError(RunColmap("gcn_model_evaluator --benchmark_path " +
                               ShellQuote(Path("none")) + " --num_threads 0"),
                     {"--num_threads must be -1 (all cores) or >= 1 (got 0)"});
}

TEST_F(BadInput, EmbeddingTrainerWordsZero) {
  ExpectOneLineError(
      RunColmap("gcn_embedding_trainer --database_paths " +
                ShellQuote(database_path_) + " --output_path " +
                ShellQuote(Path("vlad.bin")) + " --GcnEmbedding.num_words 0"),
      {"--GcnEmbedding.num_words must be >= 1 (got 0)"});
  EXPECT_FALSE(ExistsFile(Path("vlad.bin")));
}

TEST_F(BadInput, EmbeddingTrainerNumThreadsZero) {
  ExpectOneLineError(
      RunColmap("gcn_embedding_trainer --database_paths " +
                ShellQuote(database_path_) + " --output_path " +
                ShellQuote(Path("vlad.bin")) + " --GcnEmbedding.num_threads 0"),
      {"--GcnEmbedding.num_threads must be -1 (all cores) or >= 1 (got 0)"});
}

TEST_F(BadInput, EmbeddingTrainerShrinkageNegative) {
  ExpectOneLineError(RunColmap("gcn_embedding_trainer --database_paths " +
                               ShellQuote(database_path_) + " --output_path " +
                               ShellQuote(Path("vlad.bin")) +
                               " --GcnEmbedding.shrinkage -0.5"),
                     {"--GcnEmbedding.shrinkage must be >= 0 (got -0.5)"});
}

TEST_F(BadInput, VocabTreeBuilderBranchingOne) {
  ExpectOneLineError(RunColmap("gcn_vocab_tree_builder --database_paths " +
                               ShellQuote(database_path_) + " --output_path " +
                               ShellQuote(Path("tree.bin")) + " --branching 1"),
                     {"--branching must be >= 2 (got 1)"});
}

TEST_F(BadInput, VocabTreeBuilderLogInMissingFolder) {
  const std::string log = Path("no_such_folder/colmap.log");
  ExpectOneLineError(RunColmap("gcn_vocab_tree_builder --database_paths " +
                               ShellQuote(database_path_) + " --output_path " +
                               ShellQuote(Path("tree.bin")) +
                               " --colmap_log_path " + ShellQuote(log)),
                     {log, "does not exist"});
}

}  // namespace
}  // namespace colmap_gcn
