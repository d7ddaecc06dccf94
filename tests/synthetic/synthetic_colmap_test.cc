// End-to-end check of the synthetic ground truth against the real COLMAP:
// a small ordinary scene is matched exhaustively and mapped; the mapper must
// register (nearly) every image at the ground-truth poses, and geometric
// verification must agree with the ground-truth overlap. Skipped when COLMAP
// is not installed.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene/reconstruction.h"
#include "synthetic/pair_overlap.h"
#include "synthetic/scene_generator.h"
#include "synthetic_evaluation.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

class SyntheticColmapTest : public ::testing::Test {
 protected:
  static constexpr int kNumImages = 16;
  static constexpr int kNumDistractors = 2;

  static void SetUpTestSuite() {
    colmap_ = test::RealColmapExe();
    if (colmap_.empty()) {
      return;
    }
    dir_ = std::make_unique<TemporaryDirectory>("synthetic_colmap_test");
    const std::string scene = dir_->Path();
    SyntheticSceneOptions options;
    options.family = "ordinary";
    options.num_images = kNumImages;
    options.num_distractors = kNumDistractors;
    options.seed = 1;
    options.num_threads = 2;
    GenerateSyntheticScene(options, scene);

    Reconstruction gt;
    gt.ReadText(JoinPaths(scene, "gt"));
    const ModelCamera& camera = gt.cameras.begin()->second;
    const std::string params = std::to_string(camera.params[0]) + "," +
                               std::to_string(camera.params[1]) + "," +
                               std::to_string(camera.params[2]) + "," +
                               std::to_string(camera.params[3]);
    const std::string db = JoinPaths(scene, "database.db");
    const std::string images = JoinPaths(scene, "images");
    const std::string sparse = JoinPaths(scene, "sparse");
    CreateDirIfNotExists(sparse);
    const std::string exe = ShellQuote(colmap_);
    const std::vector<std::string> commands = {
        exe + " feature_extractor --database_path " + ShellQuote(db) +
            " --image_path " + ShellQuote(images) +
            " --ImageReader.single_camera 1 --ImageReader.camera_model "
            "PINHOLE --ImageReader.camera_params " +
            params +
            " --SiftExtraction.use_gpu 0 --SiftExtraction.num_threads 2"
            " --SiftExtraction.max_num_features 2048",
        exe + " exhaustive_matcher --database_path " + ShellQuote(db) +
            " --SiftMatching.use_gpu 0 --SiftMatching.num_threads 2",
        exe + " mapper --database_path " + ShellQuote(db) + " --image_path " +
            ShellQuote(images) + " --output_path " + ShellQuote(sparse) +
            " --Mapper.num_threads 1"};
    for (const std::string& command : commands) {
      std::string output;
      const int code = test::RunShell(command, &output);
      if (code != 0) {
        setup_error_ = "command failed (" + std::to_string(code) +
                       "): " + command + "\n" + output;
        return;
      }
    }
  }

  static void TearDownTestSuite() { dir_.reset(); }

  void SetUp() override {
    if (colmap_.empty()) {
      GTEST_SKIP() << "COLMAP is not installed";
    }
    ASSERT_TRUE(setup_error_.empty()) << setup_error_;
  }

  static std::string ScenePath(const std::string& relative) {
    return JoinPaths(dir_->Path(), relative);
  }

  static std::string colmap_;
  static std::unique_ptr<TemporaryDirectory> dir_;
  static std::string setup_error_;
};

std::string SyntheticColmapTest::colmap_;
std::unique_ptr<TemporaryDirectory> SyntheticColmapTest::dir_;
std::string SyntheticColmapTest::setup_error_;

TEST_F(SyntheticColmapTest, MapperRegistersImagesAtGroundTruthPoses) {
  Reconstruction gt;
  gt.ReadText(ScenePath("gt"));
  const Reconstruction model = ReadLargestModel(ScenePath("sparse"));
  const PoseAlignmentResult result = AlignToGroundTruth(gt, model);
  std::cout << "registered " << result.num_registered << "/" << kNumImages
            << ", median centre error " << result.median_position_error << " ("
            << 100.0 * result.RelativeMedianError() << "% of scene size "
            << result.scene_size << ")" << std::endl;
  EXPECT_EQ(result.num_gt_images, kNumImages);
  EXPECT_GE(result.RegisteredFraction(), 0.95)
      << result.num_registered << " of " << kNumImages << " registered";
  // COLMAP 3.8's matching and mapping are not repeatable (FLANN, RANSAC):
  // runs of this scene gave < 1 % median centre error and once 3.0 %
  // (fresh-clone CI check, machine under load); a wrong ground
  // truth (pose convention, intrinsics) or a folded model gives tens of %.
  // 5 % is the benchmark's "accurate camera" bound.
  EXPECT_LT(result.RelativeMedianError(), 0.05)
      << "median centre error " << result.median_position_error
      << " for scene size " << result.scene_size;
  // Distractors overlap nothing: the mapper must not place them.
  for (const auto& [id, image] : model.images) {
    EXPECT_TRUE(StringStartsWith(image.name, "synth_")) << image.name;
  }
}

TEST_F(SyntheticColmapTest, OverlapAgreesWithGeometricVerification) {
  const PairOverlapTable table =
      ReadPairOverlapTable(ScenePath("gt/pair_overlap.csv"));
  EXPECT_EQ(table.NumPairs(),
            static_cast<size_t>((kNumImages + kNumDistractors) *
                                (kNumImages + kNumDistractors - 1) / 2));
  const std::vector<TwoViewGeometryRow> geometries =
      ReadTwoViewGeometries(ScenePath("database.db"));
  const OverlapAgreement agreement = CompareOverlapWithVerification(
      table, geometries, {DistractorImageName(0), DistractorImageName(1)});
  std::cout << "overlap>=0.3 verified " << agreement.num_overlap_verified << "/"
            << agreement.num_overlap_pairs << ", zero-overlap verified "
            << agreement.num_zero_verified << "/" << agreement.num_zero_pairs
            << ", distractor pairs verified "
            << agreement.num_distractor_verified << "/"
            << agreement.num_distractor_pairs << std::endl;
  ASSERT_GT(agreement.num_overlap_pairs, kNumImages / 2);
  EXPECT_GE(agreement.OverlapVerifiedFraction(), 0.9)
      << agreement.num_overlap_verified << " of " << agreement.num_overlap_pairs
      << " pairs with overlap >= 0.3 verified";
  EXPECT_LE(agreement.num_zero_verified, agreement.num_zero_pairs / 20)
      << agreement.num_zero_verified << " of " << agreement.num_zero_pairs
      << " zero-overlap pairs verified";
  EXPECT_LE(agreement.num_distractor_verified, 1);
}

}  // namespace
}  // namespace colmap_gcn
