// The two commands users run first, end to end on a small generated scene:
// `colmap gcn_matcher` with the shipped default model (no model flag) and
// `colmap gcn_reconstructor`. Extraction, matching and mapping each run on
// one thread, so every run sees the same database (multi-threaded
// extraction numbers the images in completion order) and the same RANSAC
// and mapper draws: the assertions are about our pairs, not COLMAP's
// scheduling.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "e2e_scene.h"
#include "pairing/pairs_io.h"
#include "scene/database.h"
#include "scene/reconstruction.h"
#include "scene/reconstruction_stats.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

using test::RealColmapExe;
using test::RunShell;

// 20 views of the orbit: enough for the mapper to register every view from
// a selective model's pairs (the synthetic-trained model kept 46 of the 190
// pairs here, 20/20 registered; on 16 views its 32 pairs, little beyond
// each image's two best neighbours, registered 12).
const size_t kNumImages = 20;
// The default --GcnMatching.min_pairs_per_image.
const int kMinPairsPerImage = 2;

std::string ShippedModelPath() {
  return JoinPaths(COLMAP_GCN_SOURCE_DIR, "colmap_gcn/models/default.gcnmodel");
}

// Our front end first on PATH, as users run it; no $COLMAP_GCN_MODEL, so a
// run without --GcnMatching.model_path finds the model the way a user's
// does.
int Colmap(const std::string& args, std::string* output) {
  return test::RunFrontend(args, output, "-u COLMAP_GCN_MODEL");
}

// The pair ids a pairs file names, checking on the way that every name is
// an image of the database, no pair joins an image to itself and no pair is
// listed twice (in either order); *degree counts pairs per image.
std::set<image_pair_t> CheckedPairIds(const std::string& pairs_path,
                                      const std::vector<DatabaseImage>& images,
                                      std::map<std::string, int>* degree) {
  std::map<std::string, image_t> ids;
  for (const DatabaseImage& image : images) ids[image.name] = image.image_id;
  std::set<image_pair_t> pair_ids;
  for (const auto& [name1, name2] : ReadPairsFile(pairs_path)) {
    EXPECT_EQ(ids.count(name1), 1u) << name1;
    EXPECT_EQ(ids.count(name2), 1u) << name2;
    if (ids.count(name1) == 0 || ids.count(name2) == 0) continue;
    EXPECT_NE(name1, name2);
    EXPECT_TRUE(
        pair_ids.insert(ImagePairToPairId(ids.at(name1), ids.at(name2))).second)
        << name1 << " " << name2 << " listed twice";
    ++(*degree)[name1];
    ++(*degree)[name2];
  }
  return pair_ids;
}

std::set<image_pair_t> GeometryPairIds(const std::string& database_path) {
  std::set<image_pair_t> pair_ids;
  for (const auto& info : Database(database_path).ReadTwoViewGeometryInfos()) {
    pair_ids.insert(info.pair_id);
  }
  return pair_ids;
}

// Images registered in the largest model a mapper run wrote.
size_t MaxRegistered(const std::string& sparse_path) {
  size_t max_registered = 0;
  for (const std::string& model_path : ListSparseModels(sparse_path)) {
    Reconstruction reconstruction;
    reconstruction.Read(model_path);
    max_registered = std::max(max_registered, reconstruction.images.size());
  }
  return max_registered;
}

class DefaultModelEndToEnd : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (RealColmapExe().empty()) return;
    dir_ = new TemporaryDirectory("colmap_gcn_default_model_e2e");
    scene_ = new test::ExtractedScene;
    test::MakeExtractedScene(dir_->Path(), kNumImages, scene_);
    ready_ = !HasFatalFailure();
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
    delete scene_;
    scene_ = nullptr;
  }
  void SetUp() override {
    if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
    ASSERT_TRUE(ready_);
  }

  static std::string ImagePath() { return scene_->image_path; }
  static std::string BasePath() { return scene_->database_path; }

  static TemporaryDirectory* dir_;
  // The extracted scene; its extraction flags are gcn_reconstructor's too.
  static test::ExtractedScene* scene_;
  static bool ready_;
};

TemporaryDirectory* DefaultModelEndToEnd::dir_ = nullptr;
test::ExtractedScene* DefaultModelEndToEnd::scene_ = nullptr;
bool DefaultModelEndToEnd::ready_ = false;

TEST_F(DefaultModelEndToEnd, GcnMatcherWithTheShippedModel) {
  ASSERT_TRUE(ExistsFile(ShippedModelPath()));
  const std::string database_path = JoinPaths(dir_->Path(), "default.db");
  ASSERT_EQ(RunShell("cp " + BasePath() + " " + database_path), 0);
  std::string output;
  // No model flag: a run that did not find the shipped model would fail
  // with "no GCN model".
  ASSERT_EQ(Colmap("gcn_matcher --database_path " + database_path +
                       " --SiftMatching.use_gpu 0 --SiftMatching.num_threads 1",
                   &output),
            0)
      << output;
  const std::string pairs_path = database_path + ".pairs.txt";
  ASSERT_TRUE(ExistsFile(pairs_path)) << output;
  EXPECT_NE(output.find("pairs written to " + pairs_path), std::string::npos)
      << output;
  // The picture of the view graph beside the pairs file.
  EXPECT_TRUE(ExistsFile(database_path + ".pairs_view_graph.png")) << output;

  const std::vector<DatabaseImage> images =
      Database(database_path).ReadAllImages();
  ASSERT_EQ(images.size(), kNumImages);
  std::map<std::string, int> degree;
  const std::set<image_pair_t> pair_ids =
      CheckedPairIds(pairs_path, images, &degree);
  EXPECT_EQ(degree.size(), kNumImages);
  for (const auto& [name, count] : degree) {
    EXPECT_GE(count, kMinPairsPerImage) << name;
  }
  EXPECT_LE(pair_ids.size(), kNumImages * (kNumImages - 1) / 2);
  // COLMAP matched exactly the chosen pairs.
  EXPECT_EQ(GeometryPairIds(database_path), pair_ids);

  // The model it found is the shipped file: naming that file explicitly
  // gives the same pairs and scores (the pairs are all matched by now, so
  // this run only pairs).
  const std::string explicit_pairs_path =
      JoinPaths(dir_->Path(), "explicit_pairs.txt");
  ASSERT_EQ(Colmap("gcn_matcher --database_path " + database_path +
                       " --GcnMatching.model_path " + ShippedModelPath() +
                       " --GcnMatching.pairs_path " + explicit_pairs_path +
                       " --GcnMatching.write_figures 0"
                       " --SiftMatching.use_gpu 0",
                   &output),
            0)
      << output;
  EXPECT_EQ(ReadTextFile(explicit_pairs_path), ReadTextFile(pairs_path));
  EXPECT_FALSE(
      ExistsFile(JoinPaths(dir_->Path(), "explicit_pairs_view_graph.png")));

  // Every image registered in one model: the run is repeatable, so anything
  // less means the pairs lost a view.
  const std::string sparse_path = JoinPaths(dir_->Path(), "default_sparse");
  CreateDirIfNotExists(sparse_path);
  ASSERT_EQ(Colmap("mapper --database_path " + database_path +
                       " --image_path " + ImagePath() + " --output_path " +
                       sparse_path + " --Mapper.num_threads 1",
                   &output),
            0)
      << output;
  EXPECT_EQ(ListSparseModels(sparse_path).size(), 1u);
  EXPECT_EQ(MaxRegistered(sparse_path), kNumImages);
}

TEST_F(DefaultModelEndToEnd, GcnReconstructorFromImages) {
  const std::string workspace_path = JoinPaths(dir_->Path(), "workspace");
  std::string output;
  ASSERT_EQ(Colmap("gcn_reconstructor --image_path " + ImagePath() +
                       " --workspace_path " + workspace_path +
                       scene_->extraction_args +
                       " --SiftMatching.use_gpu 0 --SiftMatching.num_threads 1"
                       " --Mapper.num_threads 1",
                   &output),
            0)
      << output;
  const std::string database_path = JoinPaths(workspace_path, "database.db");
  const std::string sparse_path = JoinPaths(workspace_path, "sparse");
  // The workspace's database is one file again: no SQLite side files left.
  EXPECT_FALSE(ExistsFile(database_path + "-wal"));
  EXPECT_FALSE(ExistsFile(database_path + "-shm"));
  const std::vector<DatabaseImage> images =
      Database(database_path).ReadAllImages();
  ASSERT_EQ(images.size(), kNumImages);

  // COLMAP matched exactly the pairs gcn_matcher chose.
  std::map<std::string, int> degree;
  const std::set<image_pair_t> pair_ids =
      CheckedPairIds(database_path + ".pairs.txt", images, &degree);
  EXPECT_EQ(degree.size(), kNumImages);
  EXPECT_EQ(GeometryPairIds(database_path), pair_ids);

  // A model that reads back, with every image registered, as the report
  // says.
  ASSERT_FALSE(ListSparseModels(sparse_path).empty()) << output;
  EXPECT_EQ(MaxRegistered(sparse_path), kNumImages);
  EXPECT_NE(output.find(std::to_string(kNumImages) + "/" +
                        std::to_string(kNumImages)),
            std::string::npos)
      << output;
  // The HTML report, named in the summary, with nothing left unregistered.
  const std::string report_path = JoinPaths(workspace_path, "report.html");
  EXPECT_NE(output.find("report            " + report_path), std::string::npos)
      << output;
  EXPECT_NE(ReadTextFile(report_path).find("Images not registered (0)"),
            std::string::npos);
  EXPECT_TRUE(ExistsFile(JoinPaths(workspace_path, "run.json")));
}

}  // namespace
}  // namespace colmap_gcn
