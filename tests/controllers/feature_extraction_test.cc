#include "controllers/feature_extraction.h"

#include <gtest/gtest.h>

#include <fstream>

#include "controllers/colmap_runner.h"
#include "controllers/incremental_mapping.h"
#include "fake_colmap.h"
#include "scene/colmap_scene_fixture.h"
#include "scene/database.h"
#include "scene/database_copy.h"
#include "scene/database_inspector.h"
#include "scene/reconstruction.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"

namespace colmap_gcn {
namespace {

using test::DatabaseInspector;
using test::ExpectErrorContaining;
using test::FakeColmap;
using Arguments = std::vector<std::string>;

TEST(FeatureExtraction, PassesTheImagesThenTheUsersArguments) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  const std::string database_path = JoinPaths(dir.Path(), "database.db");
  FeatureExtractionOptions options;
  options.image_path = "/images";
  options.colmap_args = {"--SiftExtraction.max_num_features", "100"};
  const FeatureExtractionSummary summary =
      ExtractFeatures(fake.Runner(), database_path, options);
  EXPECT_EQ(fake.LastArguments(),
            (Arguments{"feature_extractor",
                       "--database_path",
                       database_path,
                       "--image_path",
                       "/images",
                       "--SiftExtraction.max_num_features",
                       "100",
                       "--SiftExtraction.use_gpu",
                       "0"}));
  EXPECT_EQ(summary.num_images, 2u);
  EXPECT_GE(summary.seconds, 0.0);
}

TEST(FeatureExtraction, ImagesLeftWithoutFeaturesAreAnError) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  fake.SetImagesWithoutFeatures(3);
  const std::string database_path = JoinPaths(dir.Path(), "database.db");
  FeatureExtractionOptions options;
  options.image_path = "/images";
  ExpectErrorContaining(
      [&] { ExtractFeatures(fake.Runner(), database_path, options); },
      "colmap feature_extractor exited 0 but 1 of the 3 images in " +
          database_path +
          " have no keypoints or descriptors (the first: img3.jpg)");
  // A scratch database that failed is not kept.
  options.replace_database = true;
  EXPECT_THROW(ExtractFeatures(fake.Runner(), database_path, options), Error);
  EXPECT_FALSE(ExistsFile(database_path + ".partial"));
}

TEST(FeatureExtraction, FewerImagesThanReportedAreAnError) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  fake.PrintOnEveryRun(
      "Processed file [1/3]\n  Features:        10\n"
      "Processed file [2/3]\n  Features:        12\n"
      "Processed file [3/3]\n  Features:        11\n");
  FeatureExtractionOptions options;
  options.image_path = "/images";
  ExpectErrorContaining(
      [&] {
        ExtractFeatures(
            fake.Runner(), JoinPaths(dir.Path(), "database.db"), options);
      },
      "colmap feature_extractor reported 3 images extracted but");
}

TEST(FeatureExtraction, ImageListAndSingleCamera) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  const std::string database_path = JoinPaths(dir.Path(), "database.db");
  FeatureExtractionOptions options;
  options.image_path = "/images";
  options.image_list_path = "/list.txt";
  options.single_camera = true;
  ExtractFeatures(fake.Runner(), database_path, options);
  EXPECT_EQ(fake.LastArguments(),
            (Arguments{"feature_extractor",
                       "--database_path",
                       database_path,
                       "--image_path",
                       "/images",
                       "--image_list_path",
                       "/list.txt",
                       "--ImageReader.single_camera",
                       "1",
                       "--SiftExtraction.use_gpu",
                       "0"}));

  // Off: COLMAP's own default (one camera per image) applies.
  options.image_list_path = "";
  options.single_camera = false;
  ExtractFeatures(fake.Runner(), database_path, options);
  EXPECT_EQ(fake.LastArguments(),
            (Arguments{"feature_extractor",
                       "--database_path",
                       database_path,
                       "--image_path",
                       "/images",
                       "--SiftExtraction.use_gpu",
                       "0"}));
}

TEST(FeatureExtraction, ReplaceDatabaseRenamesOnlyACompleteExtraction) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  const std::string database_path = JoinPaths(dir.Path(), "base.db");
  std::ofstream(database_path) << "an earlier, unfinished database";
  std::ofstream(database_path + "-wal") << "its log";
  FeatureExtractionOptions options;
  options.image_path = "/images";
  options.replace_database = true;
  fake.SetExtractedImages(3);
  EXPECT_EQ(ExtractFeatures(fake.Runner(), database_path, options).num_images,
            3u);
  // COLMAP wrote the scratch file, which then replaced the database.
  const Arguments args = fake.LastArguments();
  ASSERT_GE(args.size(), 3u);
  EXPECT_EQ(args[2], database_path + ".partial");
  EXPECT_FALSE(ExistsFile(database_path + ".partial"));
  EXPECT_EQ(Database(database_path).NumImages(), 3u);

  // A failed extraction leaves no database behind to be trusted later.
  fake.FailRuns();
  EXPECT_THROW(ExtractFeatures(fake.Runner(), database_path, options), Error);
  EXPECT_FALSE(ExistsFile(database_path));
  EXPECT_FALSE(ExistsFile(database_path + ".partial"));
}

TEST(FeatureExtraction, TooFewImagesIsAnError) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  const std::string database_path = JoinPaths(dir.Path(), "database.db");
  FeatureExtractionOptions options;
  options.image_path = "/images";
  fake.SetExtractedImages(1);
  ExpectErrorContaining(
      [&] { ExtractFeatures(fake.Runner(), database_path, options); },
      "colmap feature_extractor read 1 image(s) from /images; at least 2 "
      "readable images are needed");
  options.min_num_images = 0;
  RemoveDatabaseFiles(database_path);
  EXPECT_EQ(ExtractFeatures(fake.Runner(), database_path, options).num_images,
            1u);
}

TEST(FeatureExtraction, CheckNamesTheField) {
  FeatureExtractionOptions options;
  ExpectErrorContaining([&] { options.Check(); }, "image_path");
  options.image_path = "/images";
  options.min_num_images = -1;
  ExpectErrorContaining([&] { options.Check(); }, "min_num_images");
}

TEST(CheckImageFolder, NeedsAFolderWithAFile) {
  TemporaryDirectory dir;
  const std::string missing = JoinPaths(dir.Path(), "missing");
  ExpectErrorContaining([&] { CheckImageFolder(missing); },
                        "image folder not found: " + missing);
  const std::string images = JoinPaths(dir.Path(), "images");
  CreateDirIfNotExists(JoinPaths(images, "empty_subfolder"));
  ExpectErrorContaining([&] { CheckImageFolder(images); },
                        "image folder " + images + " holds no files");
  // COLMAP's reader walks subfolders, so a file in one is enough.
  std::ofstream(JoinPaths(JoinPaths(images, "empty_subfolder"), "a.jpg"))
      << "x";
  EXPECT_NO_THROW(CheckImageFolder(images));
}

// The real COLMAP through both controllers: four small overlapping crops of
// one texture, extracted and mapped on one thread each, register in one
// model.
TEST(FeatureExtractionColmap, ExtractsAndMapsOverlappingImages) {
  const std::string colmap_exe = test::RealColmapExe();
  if (colmap_exe.empty()) GTEST_SKIP() << "COLMAP not installed";
  TemporaryDirectory dir;
  const std::string images = JoinPaths(dir.Path(), "images");
  CreateDirIfNotExists(images);
  const int kNumImages = 4;
  test::WriteOverlappingTestImages(images,
                                   kNumImages,
                                   /*width=*/320,
                                   /*height=*/240,
                                   /*step_x=*/30,
                                   /*step_y=*/20);
  ColmapRunnerOptions runner_options;
  runner_options.colmap_exe = colmap_exe;
  runner_options.log_path = JoinPaths(dir.Path(), "colmap.log");
  runner_options.show_progress = false;
  const ColmapRunner colmap(runner_options);
  const std::string database_path = JoinPaths(dir.Path(), "database.db");

  FeatureExtractionOptions extraction;
  extraction.image_path = images;
  extraction.single_camera = true;
  extraction.replace_database = true;
  extraction.colmap_args = {"--SiftExtraction.num_threads",
                            "1",
                            "--SiftExtraction.max_num_features",
                            "1024"};
  const FeatureExtractionSummary extracted =
      ExtractFeatures(colmap, database_path, extraction);
  EXPECT_EQ(extracted.num_images, static_cast<size_t>(kNumImages));
  EXPECT_EQ(DatabaseInspector(database_path).NumCameras(), 1u);
  EXPECT_GT(DatabaseInspector(database_path).NumKeypoints(), 0u);

  colmap.Run(
      "exhaustive_matcher",
      {"--database_path", database_path, "--SiftMatching.num_threads", "1"});

  IncrementalMappingOptions mapping;
  mapping.image_path = images;
  mapping.num_threads = 1;
  mapping.min_model_size = 3;
  const std::string sparse_path = JoinPaths(dir.Path(), "sparse");
  const IncrementalMappingSummary mapped =
      RunIncrementalMapping(colmap, database_path, sparse_path, mapping);
  ASSERT_EQ(mapped.model_paths,
            std::vector<std::string>{JoinPaths(sparse_path, "0")});
  Reconstruction model;
  model.Read(mapped.model_paths[0]);
  // Crops of one image have no parallax to triangulate from: what the test
  // can rely on is that every image registers.
  EXPECT_EQ(model.images.size(), static_cast<size_t>(kNumImages));
}

}  // namespace
}  // namespace colmap_gcn
