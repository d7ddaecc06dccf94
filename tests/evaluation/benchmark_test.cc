// `colmap gcn_benchmark` end to end on a small generated scene, its numbers
// cross-checked against `colmap model_analyzer` and direct SQL counts on
// the same databases. Skips without COLMAP.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "evaluation/common_tracks.h"
#include "evaluation/ground_truth.h"
#include "evaluation/json_file.h"
#include "evaluation/pose_pair_filter.h"
#include "scene/colmap_scene_fixture.h"
#include "scene/database.h"
#include "scene/reconstruction_stats.h"
#include "synthetic/pair_overlap.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

using test::FrontendExe;
using test::QuerySqlInt;
using test::RealColmapExe;
using test::RunShell;

const char* kScene = "synth-ordinary-10-s7";

int RunBenchmark(const std::string& out, std::string* output) {
  return RunShell(ShellQuote(FrontendExe()) +
                      " gcn_benchmark --datasets synth:ordinary:10:7"
                      " --methods exhaustive,knn:5,oracle"
                      " --output_path " +
                      ShellQuote(out) +
                      " --SiftExtraction.num_threads 2"
                      " --SiftMatching.num_threads 2",
                  output);
}

// The number after "<key>:" in model_analyzer's output, or -1.
double AnalyzerValue(const std::string& output, const std::string& key) {
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    const size_t pos = line.find(key + ":");
    if (pos == std::string::npos) continue;
    return std::atof(line.substr(pos + key.size() + 1).c_str());
  }
  return -1;
}

class GcnBenchmarkEndToEnd : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (RealColmapExe().empty()) return;
    dir_ = new TemporaryDirectory("colmap_gcn_benchmark");
    first_exit_ = RunBenchmark(Out(), &first_output_);
    if (first_exit_ == 0) {
      results_ = new Json(ReadJsonFile(JoinPaths(Out(), "results.json")));
    }
  }
  static void TearDownTestSuite() {
    delete results_;
    results_ = nullptr;
    delete dir_;
    dir_ = nullptr;
  }
  void SetUp() override {
    if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
    ASSERT_EQ(first_exit_, 0) << first_output_;
    ASSERT_NE(results_, nullptr);
  }

  static std::string Out() { return JoinPaths(dir_->Path(), "out"); }
  static std::string SceneDir() { return JoinPaths(Out(), kScene); }
  static const Json& Methods() {
    return results_->at("scenes").at(0).at("methods");
  }
  static const Json& Method(const std::string& spec) {
    for (const Json& method : Methods()) {
      if (method.at("method").get<std::string>() == spec) return method;
    }
    throw std::runtime_error("no method " + spec);
  }

  static TemporaryDirectory* dir_;
  static int first_exit_;
  static std::string first_output_;
  static Json* results_;
};

TemporaryDirectory* GcnBenchmarkEndToEnd::dir_ = nullptr;
int GcnBenchmarkEndToEnd::first_exit_ = -1;
std::string GcnBenchmarkEndToEnd::first_output_;
Json* GcnBenchmarkEndToEnd::results_ = nullptr;

TEST_F(GcnBenchmarkEndToEnd, PrintsAndWritesAllTables) {
  for (const char* table : {"Matchable image retrieval",
                            "Matching (Tables 3, 5)",
                            "Mapping, largest model",
                            "Cameras against ground truth",
                            "Average over scenes"}) {
    EXPECT_NE(first_output_.find(table), std::string::npos) << table;
  }
  const std::string report = ReadTextFile(JoinPaths(Out(), "report.md"));
  EXPECT_NE(report.find("| oracle |"), std::string::npos) << report;
  EXPECT_TRUE(ExistsFile(JoinPaths(Out(), "results.csv")));
  EXPECT_TRUE(ExistsFile(JoinPaths(
      Out(), std::string("figures/") + kScene + "/exhaustive_view_graph.png")));
  // The scene folder holds no empty SQLite side files of the benchmark's
  // reads, neither beside base.db nor under its extraction's scratch name.
  for (const std::string db : {"base.db", "base.db.partial"}) {
    for (const std::string suffix : {"-wal", "-shm"}) {
      EXPECT_FALSE(ExistsFile(JoinPaths(SceneDir(), db + suffix)))
          << db + suffix;
    }
  }
}

TEST_F(GcnBenchmarkEndToEnd, NumbersMatchModelAnalyzerAndSql) {
  int checked = 0;
  for (const std::string spec : {"exhaustive", "oracle"}) {
    const Json& method = Method(spec);
    ASSERT_EQ(method.at("status").get<std::string>(), "ok") << spec;
    const std::string db =
        JoinPaths(JoinPaths(SceneDir(), spec), "database.db");
    // Every pair in a fresh copy of the extracted database was attempted by
    // this method; verified pairs as COLMAP's mapper uses them.
    EXPECT_EQ(method.at("tam").get<int64_t>(),
              QuerySqlInt(db, "SELECT COUNT(*) FROM two_view_geometries"))
        << spec;
    int64_t num_verified = 0;
    for (const TwoViewGeometryInfo& info :
         Database(db).ReadTwoViewGeometryInfos()) {
      num_verified += IsVerifiedTwoViewGeometry(info.config, info.num_inliers);
    }
    // UM counts COLMAP's verifications; the look-alike filter then hides
    // some of them from the mapper (their rows made unverified).
    EXPECT_EQ(method.at("um").get<int64_t>(),
              num_verified + method.at("lookalike_removed").get<int64_t>())
        << spec;
    EXPECT_EQ(method.at("retrieval").at("num_pairs").get<int64_t>(),
              method.at("tam").get<int64_t>());
    const Json& sfm = method.at("sfm");
    EXPECT_EQ(sfm.at("num_images").get<int64_t>(),
              QuerySqlInt(db, "SELECT COUNT(*) FROM images"));
    const std::string model = sfm.at("largest_model_path").get<std::string>();
    ASSERT_FALSE(model.empty()) << spec;
    std::string analyzer;
    ASSERT_EQ(RunShell(ShellQuote(RealColmapExe()) + " model_analyzer --path " +
                           ShellQuote(model),
                       &analyzer),
              0)
        << analyzer;
    EXPECT_EQ(sfm.at("num_registered").get<int64_t>(),
              AnalyzerValue(analyzer, "Registered images"));
    EXPECT_EQ(sfm.at("num_points3D").get<int64_t>(),
              AnalyzerValue(analyzer, "Points"));
    EXPECT_EQ(sfm.at("num_observations").get<int64_t>(),
              AnalyzerValue(analyzer, "Observations"));
    EXPECT_NEAR(sfm.at("mean_track_length").get<double>(),
                AnalyzerValue(analyzer, "Mean track length"),
                1e-5);
    EXPECT_NEAR(sfm.at("mean_reprojection_error").get<double>(),
                AnalyzerValue(analyzer, "Mean reprojection error"),
                1e-5);
    EXPECT_EQ(
        sfm.at("num_models").get<int64_t>(),
        static_cast<int64_t>(
            ListSparseModels(JoinPaths(JoinPaths(SceneDir(), spec), "sparse"))
                .size()));
    // Pose errors against the synthetic ground truth cover exactly the
    // registered images of the largest model.
    const Json& pose = sfm.at("pose_errors");
    EXPECT_EQ(pose.at("num_gt_images").get<int64_t>(), 10);
    EXPECT_EQ(pose.at("num_evaluated").get<int64_t>(),
              sfm.at("num_registered").get<int64_t>());
    if (sfm.at("num_registered").get<int64_t>() >= 3) {
      EXPECT_TRUE(pose.at("aligned").get<bool>());
    }
    ++checked;
  }
  EXPECT_EQ(checked, 2);
  // Exhaustive: all N(N-1)/2 pairs; recall 1 by construction.
  EXPECT_EQ(Method("exhaustive").at("tam").get<int64_t>(), 45);
  EXPECT_DOUBLE_EQ(
      Method("exhaustive").at("retrieval").at("recall").get<double>(), 1.0);
}

TEST_F(GcnBenchmarkEndToEnd, OracleHasTheBestUsefulRatio) {
  const Json& oracle = Method("oracle");
  ASSERT_EQ(oracle.at("status").get<std::string>(), "ok");
  EXPECT_DOUBLE_EQ(oracle.at("retrieval").at("precision").get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(oracle.at("retrieval").at("recall").get<double>(), 1.0);
  const double oracle_ratio = oracle.at("um_over_tam").get<double>();
  for (const Json& method : Methods()) {
    if (method.at("status").get<std::string>() != "ok") continue;
    EXPECT_GE(oracle_ratio, method.at("um_over_tam").get<double>())
        << method.at("method").get<std::string>();
  }
}

TEST_F(GcnBenchmarkEndToEnd, SecondRunReadsTheCache) {
  const std::string log = JoinPaths(SceneDir(), "colmap.log");
  ASSERT_TRUE(ExistsFile(log));
  const std::string before = ReadTextFile(log);
  std::string output;
  ASSERT_EQ(RunBenchmark(Out(), &output), 0) << output;
  // No COLMAP command ran again: the log of every COLMAP call is unchanged.
  EXPECT_EQ(ReadTextFile(log), before);
  EXPECT_NE(output.find("features cached"), std::string::npos) << output;
  EXPECT_NE(output.find("exhaustive: matching cached"), std::string::npos);
  const Json again = ReadJsonFile(JoinPaths(Out(), "results.json"));
  const Json& methods = again.at("scenes").at(0).at("methods");
  EXPECT_EQ(methods, Methods());
}

// SIGTERM while a method is being matched (or mapped): the run stops with
// 128 + 15, caches nothing for that method, starts no later method, and
// the next run redoes the method to the uninterrupted result.
TEST_F(GcnBenchmarkEndToEnd, InterruptedMethodIsNotCachedAndTheRunStops) {
  const std::string out = JoinPaths(dir_->Path(), "interrupted");
  ASSERT_EQ(RunShell("cp -a " + ShellQuote(Out()) + " " + ShellQuote(out)), 0);
  const std::string scene = JoinPaths(out, kScene);
  std::filesystem::remove_all(JoinPaths(scene, "knn-5"));
  std::filesystem::remove_all(JoinPaths(scene, "oracle"));
  const std::string log = JoinPaths(dir_->Path(), "interrupted.log");
  // Waits for COLMAP to be matching knn:5's working copy, then sends
  // SIGTERM to the benchmark (which forwards it); prints its exit status.
  std::string status;
  ASSERT_EQ(
      RunShell(
          "( exec " + ShellQuote(FrontendExe()) +
              " gcn_benchmark --datasets synth:ordinary:10:7"
              " --methods exhaustive,knn:5,oracle --output_path " +
              ShellQuote(out) +
              " --SiftExtraction.num_threads 2 --SiftMatching.num_threads 2"
              " > " +
              ShellQuote(log) +
              " 2>&1 ) & pid=$!; "
              "while kill -0 $pid 2>/dev/null && ! pgrep -f " +
              // [m]: the pattern must not match this shell's command line.
              ShellQuote("[m]atches_importer.*" +
                         JoinPaths(scene, "knn-5/database.db.gcn-partial")) +
              " >/dev/null; do sleep 0.02; done; kill -TERM $pid; wait $pid; "
              "echo $?",
          &status),
      0);
  EXPECT_EQ(StringTrim(status), "143") << ReadTextFile(log);
  EXPECT_NE(ReadTextFile(log).find("interrupted (signal 15)"),
            std::string::npos)
      << ReadTextFile(log);
  const std::string run = JoinPaths(scene, "knn-5/run.json");
  if (ExistsFile(run)) {
    // Interrupted while mapping: the matching is kept, the mapping is not.
    const Json cached = ReadJsonFile(run);
    EXPECT_EQ(cached.value("status", std::string()), "ok") << cached.dump();
    EXPECT_FALSE(cached.contains("mapping_seconds")) << cached.dump();
  }
  EXPECT_FALSE(ExistsFile(JoinPaths(scene, "oracle")));

  std::string output;
  ASSERT_EQ(RunShell(ShellQuote(FrontendExe()) +
                         " gcn_benchmark --datasets synth:ordinary:10:7"
                         " --methods exhaustive,knn:5,oracle --output_path " +
                         ShellQuote(out) +
                         " --SiftExtraction.num_threads 2"
                         " --SiftMatching.num_threads 2",
                     &output),
            0)
      << output;
  const Json again = ReadJsonFile(JoinPaths(out, "results.json"));
  int found = 0;
  for (const Json& method : again.at("scenes").at(0).at("methods")) {
    if (method.at("method").get<std::string>() != "knn:5") continue;
    ++found;
    EXPECT_EQ(method.at("status").get<std::string>(), "ok");
    EXPECT_EQ(method.at("tam"), Method("knn:5").at("tam"));
    EXPECT_EQ(method.at("sfm").at("num_registered"),
              Method("knn:5").at("sfm").at("num_registered"));
  }
  EXPECT_EQ(found, 1);
}

TEST_F(GcnBenchmarkEndToEnd, GroundTruthTriangulationAgreesWithOverlaps) {
  // The GT-camera label path (used for real scenes) on the synthetic
  // scene, whose exact overlaps are known.
  Reconstruction gt;
  gt.Read(JoinPaths(SceneDir(), "gt"));
  ColmapRunnerOptions runner_options;
  runner_options.show_progress = false;
  const ColmapRunner colmap(runner_options);
  const Reconstruction triangulated =
      TriangulateOnGroundTruth(colmap,
                               gt,
                               JoinPaths(SceneDir(), "exhaustive/database.db"),
                               JoinPaths(dir_->Path(), "gt_triangulation"));
  ASSERT_EQ(triangulated.images.size(), gt.images.size());
  const ReconstructionStatistics stats =
      ComputeReconstructionStatistics(triangulated);
  EXPECT_GT(stats.num_points3D, 100u);
  EXPECT_LT(stats.mean_reprojection_error, 1.0);  // the GT is consistent
  std::vector<std::string> names;
  for (const auto& [id, image] : gt.images) names.push_back(image.name);
  const PairLabels labels =
      LabelsFromReconstruction(triangulated, names, "GT cameras");
  const PairOverlapTable overlaps =
      ReadPairOverlapTable(JoinPaths(SceneDir(), "gt/pair_overlap.csv"));
  // Pairs with large exact overlap share triangulated points; pairs that
  // share no surface share no point.
  for (const PairOverlap& pair : overlaps.Pairs()) {
    if (pair.MinOverlap() >= 0.5) {
      EXPECT_GT(labels.Evidence(pair.name1, pair.name2).common_track_ratio, 0.0)
          << pair.name1 << " " << pair.name2;
    }
    if (pair.num_shared == 0) {
      EXPECT_TRUE(labels.SharesNothing(pair.name1, pair.name2))
          << pair.name1 << " " << pair.name2;
    }
  }
}

TEST_F(GcnBenchmarkEndToEnd, PoseFilteredLabelMatchingMatchesOnlyKeptPairs) {
  Reconstruction gt;
  gt.Read(JoinPaths(SceneDir(), "gt"));
  ColmapRunnerOptions runner_options;
  runner_options.show_progress = false;
  const ColmapRunner colmap(runner_options);
  // The threshold halfway up the scene's bounds, so that the rule keeps
  // some pairs and skips others.
  double max_bound = 0;
  for (const auto& [id1, image1] : gt.images) {
    for (const auto& [id2, image2] : gt.images) {
      max_bound =
          std::max(max_bound,
                   MinViewpointChangeDeg(image1,
                                         gt.cameras.at(image1.camera_id),
                                         image2,
                                         gt.cameras.at(image2.camera_id)));
    }
  }
  ASSERT_GT(max_bound, 0.0) << "no pair of this scene can be skipped";
  PosePairFilterOptions options;
  options.max_viewpoint_change_deg = max_bound / 2;
  const PosePairSelection selection = SelectPosePairs(gt, options);
  ASSERT_GT(selection.num_skipped, 0u);
  ASSERT_GT(selection.kept.size(), 0u);
  const std::string work_dir = JoinPaths(dir_->Path(), "label_matching");
  PairMatchingOptions args;
  args.colmap_args = {"--SiftMatching.num_threads", "2"};
  const LabelMatchingSummary first = MatchPosePairsForLabels(
      colmap, JoinPaths(SceneDir(), "base.db"), gt, options, args, work_dir);
  EXPECT_EQ(first.num_images, 10u);
  EXPECT_EQ(first.num_gt_images, 10u);
  EXPECT_EQ(first.num_pairs_total, 45u);
  EXPECT_EQ(first.num_pairs_matched, selection.kept.size());
  EXPECT_GT(first.matching_seconds, 0.0);
  // COLMAP saw exactly the kept pairs.
  EXPECT_EQ(QuerySqlInt(first.database_path,
                        "SELECT COUNT(*) FROM two_view_geometries"),
            static_cast<int64_t>(selection.kept.size()));
  const Json record = ReadJsonFile(JoinPaths(work_dir, "label_matching.json"));
  EXPECT_EQ(record.value("pairs_skipped", int64_t{-1}),
            static_cast<int64_t>(selection.num_skipped));
  // A second run finds every pair matched in the same database.
  const LabelMatchingSummary again = MatchPosePairsForLabels(
      colmap, JoinPaths(SceneDir(), "base.db"), gt, options, args, work_dir);
  EXPECT_EQ(again.num_pairs_matched, first.num_pairs_matched);
  EXPECT_EQ(again.matching_seconds, 0.0);
}

}  // namespace
}  // namespace colmap_gcn

namespace colmap_gcn {
namespace {

// Pairs of a pairs file whose images carry different "<scene>__" prefixes,
// counted here from the file rather than by the code under test.
size_t CrossScenePairsInFile(const std::string& path) {
  std::istringstream lines(ReadTextFile(path));
  std::string name1, name2;
  size_t count = 0;
  while (lines >> name1 >> name2) {
    if (name1.substr(0, name1.find("__")) !=
        name2.substr(0, name2.find("__"))) {
      ++count;
    }
  }
  return count;
}

// scripts/research/collection_benchmark.sh on two small generated places:
// each alone with exhaustive matching, merged, and the merged collection's
// report.
TEST(CollectionBenchmarkScript, ComparesTheCollectionWithItsScenesAlone) {
  if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
  const TemporaryDirectory dir("colmap_gcn_collection");
  const std::string places = JoinPaths(dir.Path(), "places");
  for (const auto& [name, seed] :
       std::vector<std::pair<std::string, int>>{{"alpha", 3}, {"beta", 4}}) {
    std::string output;
    ASSERT_EQ(RunShell(ShellQuote(FrontendExe()) + " gcn_synth --output_path " +
                           ShellQuote(JoinPaths(places, name)) +
                           " --GcnSynth.num_images 8 --GcnSynth.seed " +
                           std::to_string(seed),
                       &output),
              0)
        << output;
  }
  // gamma: three blank photos without ground truth: no features, no model
  // alone, so no labels; it is left out of the collection.
  const std::string gamma = JoinPaths(places, "gamma/images");
  std::filesystem::create_directories(gamma);
  for (int i = 0; i < 3; ++i) {
    std::string pgm = "P2\n64 64\n255\n";
    for (int p = 0; p < 64 * 64; ++p) pgm += "128\n";
    WriteFileAtomically(JoinPaths(gamma, std::to_string(i) + ".pgm"), pgm);
  }
  const std::string out = JoinPaths(dir.Path(), "out");
  const std::string build =
      std::filesystem::path(FrontendExe()).parent_path().parent_path();
  const std::string command =
      "COLMAP_GCN_BUILD=" + ShellQuote(build) + " bash " +
      ShellQuote(JoinPaths(COLMAP_GCN_SOURCE_DIR,
                           "scripts/research/collection_benchmark.sh")) +
      " " + ShellQuote(out) + " knn:3 " +
      ShellQuote(JoinPaths(places, "alpha")) + " " +
      ShellQuote(JoinPaths(places, "beta")) + " " +
      ShellQuote(JoinPaths(places, "gamma")) +
      " -- --SiftExtraction.num_threads 2 --SiftMatching.num_threads 2";
  std::string output;
  ASSERT_EQ(RunShell(command, &output), 0) << output;
  EXPECT_NE(output.find("gamma left out: no labels alone"), std::string::npos)
      << output;

  const Json alone = ReadJsonFile(JoinPaths(out, "alone/results.json"));
  const Json run = ReadJsonFile(JoinPaths(out, "run/results.json"));
  ASSERT_EQ(run.at("scenes").size(), 1u);
  const Json& collection = run.at("scenes").at(0);
  EXPECT_EQ(collection.at("num_images").get<int>(), 16);
  ASSERT_TRUE(collection.value("is_collection", false));
  EXPECT_EQ(collection.at("registered_alone").size(), 2u);
  for (const Json& scene : alone.at("scenes")) {
    const std::string name = scene.at("name").get<std::string>();
    if (name == "gamma") continue;
    EXPECT_EQ(collection.at("registered_alone").at(name).get<int>(),
              scene.at("methods").at(0).at("sfm").at("num_registered"))
        << name;
  }
  const Json& knn = collection.at("methods").at(0);
  ASSERT_EQ(knn.at("status").get<std::string>(), "ok") << knn.dump();
  EXPECT_EQ(
      knn.at("cross_scene_attempted").get<size_t>(),
      CrossScenePairsInFile(JoinPaths(out, "run/collection/knn-3/pairs.txt")));
  const Json& scenes = knn.at("collection").at("scenes");
  EXPECT_EQ(scenes.at("alpha").at("num_images").get<int>(), 8);
  EXPECT_EQ(scenes.at("beta").at("num_images").get<int>(), 8);
  EXPECT_LE(scenes.at("alpha").at("num_registered").get<int>(), 8);
  const std::string report = ReadTextFile(JoinPaths(out, "run/report.md"));
  EXPECT_NE(report.find("### Collection"), std::string::npos) << report;
  EXPECT_NE(report.find("**estimated**, 120 pairs"), std::string::npos)
      << report;

  // A second run resumes from the caches and reports the same.
  ASSERT_EQ(RunShell(command, &output), 0) << output;
  EXPECT_NE(output.find("matching cached"), std::string::npos) << output;
  EXPECT_EQ(ReadJsonFile(JoinPaths(out, "run/results.json"))
                .at("scenes")
                .at(0)
                .at("methods")
                .at(0)
                .at("cross_scene_attempted"),
            knn.at("cross_scene_attempted"));
}

}  // namespace
}  // namespace colmap_gcn
