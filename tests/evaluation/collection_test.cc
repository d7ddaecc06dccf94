#include "evaluation/collection.h"

#include <gtest/gtest.h>

#include "evaluation/report.h"
#include "evaluation/results.h"

namespace colmap_gcn {
namespace {

Reconstruction ModelOf(const std::vector<std::string>& names) {
  Reconstruction model;
  image_t image_id = 1;
  for (const std::string& name : names) {
    model.images[image_id].image_id = image_id;
    model.images[image_id].name = name;
    ++image_id;
  }
  return model;
}

TEST(Collection, SceneFromThePrefix) {
  EXPECT_EQ(CollectionScene("fox__0001.jpg"), "fox");
  EXPECT_EQ(CollectionScene("a__b__c.jpg"), "a");
  EXPECT_EQ(CollectionScene("0001.jpg"), "");
  EXPECT_EQ(CollectionScenes({"b__1", "a__1", "b__2", "3"}),
            (std::set<std::string>{"", "a", "b"}));
  EXPECT_TRUE(IsMergedCollection({"a__1.jpg", "b__1.jpg"}));
  // One scene, or a name without a scene, is not a collection.
  EXPECT_FALSE(IsMergedCollection({"a__1.jpg", "a__2.jpg"}));
  EXPECT_FALSE(IsMergedCollection({"a__1.jpg", "b__1.jpg", "2.jpg"}));
  EXPECT_FALSE(IsMergedCollection({}));
}

TEST(Collection, CountsCrossScenePairs) {
  EXPECT_EQ(CountCrossScenePairs({{"a__1", "a__2"},
                                  {"a__1", "b__1"},
                                  {"b__2", "a__2"},
                                  {"b__1", "b__2"}}),
            2u);
  EXPECT_EQ(CountCrossScenePairs({}), 0u);
}

TEST(Collection, RegistrationCountsEachScenesBestModel) {
  const std::vector<std::string> names = {
      "a__1", "a__2", "a__3", "a__4", "b__1", "b__2", "c__1", "c__2"};
  // a is split over two models (3 + 1), the second also holds b: mixed;
  // c registers nowhere.
  const std::vector<Reconstruction> models = {
      ModelOf({"a__1", "a__2", "a__3"}),
      ModelOf({"a__4", "b__1", "b__2", "unknown__9"})};
  const CollectionRegistration registration =
      CountCollectionRegistration(names, models);
  EXPECT_EQ(registration.num_models, 2u);
  EXPECT_EQ(registration.num_mixed_models, 1u);
  ASSERT_EQ(registration.scenes.size(), 3u);
  EXPECT_EQ(registration.scenes.at("a").num_images, 4u);
  EXPECT_EQ(registration.scenes.at("a").num_registered, 3u);
  EXPECT_EQ(registration.scenes.at("a").num_models, 2u);
  EXPECT_EQ(registration.scenes.at("b").num_registered, 2u);
  EXPECT_EQ(registration.scenes.at("b").num_models, 1u);
  EXPECT_EQ(registration.scenes.at("c").num_images, 2u);
  EXPECT_EQ(registration.scenes.at("c").num_registered, 0u);
  EXPECT_EQ(registration.scenes.at("c").num_models, 0u);
}

TEST(Collection, ReportComparesWithTheScenesAlone) {
  BenchmarkResults results;
  results.methods = {"knn:5", "gcn"};
  SceneResult scene;
  scene.name = "collection";
  scene.kind = "images";
  scene.num_images = 101;  // 5050 pairs
  scene.is_collection = true;
  scene.registered_alone = {{"a", 40}, {"b", 20}};
  MethodResult knn;
  knn.method = "knn:5";
  knn.num_attempted = 300;
  knn.num_cross_scene_attempted = 30;
  knn.matching_seconds = 60;
  knn.collection.num_models = 2;
  knn.collection.scenes["a"] = {60, 40, 1};
  knn.collection.scenes["b"] = {41, 20, 1};
  MethodResult gcn = knn;
  gcn.method = "gcn";
  gcn.num_attempted = 100;
  gcn.num_cross_scene_attempted = 1;
  gcn.matching_seconds = 20;
  gcn.collection.scenes["b"].num_registered = 18;  // < 0.95 x 20
  scene.methods = {knn, gcn};
  results.scenes.push_back(scene);
  const std::string report = FormatBenchmarkReport(results);
  // 80 s over 400 pairs: 0.2 s per pair, x 5050 pairs.
  EXPECT_NE(report.find("**estimated**, 5050 pairs x 0.200 s"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("= 1010 s"), std::string::npos) << report;
  EXPECT_NE(report.find("| knn:5 | 300 | 30 | 10.00 | 0 | 60.0 | 0.059 | 2 "
                        "| 0 | 2/2 |"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("| gcn | 100 | 1 | 1.00 | 0 | 20.0 | 0.020 | 2 | 0 "
                        "| 1/2 |"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("| b | 41 | 20 | 20 | **18** |"), std::string::npos)
      << report;
}

TEST(Collection, EstimateCountsEveryRunOnceAndRunsWithoutAModel) {
  BenchmarkResults results;
  results.methods = {"knn:5", "knn:50", "gcn"};
  SceneResult scene;
  scene.name = "collection";
  scene.kind = "images";
  scene.num_images = 101;  // 5050 pairs
  scene.is_collection = true;
  MethodResult knn;
  knn.method = "knn:5";
  knn.num_attempted = 300;
  knn.matching_seconds = 60;
  // A row that repeats knn:5's run must not count its seconds twice.
  MethodResult copy = knn;
  copy.method = "knn:50";
  copy.message = "same pairs as knn:5";
  copy.same_as = "knn:5";
  // A run whose mapper built no model still matched its pairs.
  MethodResult gcn = knn;
  gcn.method = "gcn";
  gcn.num_attempted = 100;
  gcn.matching_seconds = 40;
  gcn.message = "mapper produced no model";
  scene.methods = {knn, copy, gcn};
  results.scenes.push_back(scene);
  const std::string report = FormatBenchmarkReport(results);
  // (60 + 40) s over 300 + 100 pairs; the copy counted would give 0.229,
  // the run without a model left out 0.200.
  EXPECT_NE(report.find("**estimated**, 5050 pairs x 0.250 s"),
            std::string::npos)
      << report;
}

}  // namespace
}  // namespace colmap_gcn
