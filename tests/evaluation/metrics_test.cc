#include "evaluation/metrics.h"

#include <gtest/gtest.h>

#include "evaluation/labels.h"
#include "evaluation/method.h"
#include "evaluation/report.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

// Five images; matchable: ab (CT .5), bc (CT .2), cd (CT .15 exactly);
// ae shares a little (CT .05, not matchable); everything else shares
// nothing.
PairLabels MakeLabels() {
  PairLabels labels({"a", "b", "c", "d", "e"}, false, true);
  labels.SetCommonTrackRatio("a", "b", 0.5);
  labels.SetCommonTrackRatio("c", "b", 0.2);
  labels.SetCommonTrackRatio("c", "d", 0.15);
  labels.SetCommonTrackRatio("a", "e", 0.05);
  return labels;
}

TEST(PairLabels, ThresholdsAndNothingShared) {
  const PairLabels labels = MakeLabels();
  PairLabelOptions options;
  EXPECT_TRUE(labels.IsMatchable("b", "a", options));
  EXPECT_TRUE(labels.IsMatchable("c", "d", options));  // >= is matchable
  EXPECT_FALSE(labels.IsMatchable("a", "e", options));
  EXPECT_FALSE(labels.SharesNothing("a", "e"));
  EXPECT_TRUE(labels.SharesNothing("a", "d"));
  EXPECT_FALSE(labels.IsLabelled("a", "z"));
  EXPECT_FALSE(labels.SharesNothing("a", "z"));  // unknown is not wrong
  EXPECT_EQ(labels.MatchablePairs(options).size(), 3u);
  options.min_common_track_ratio = 0.3;
  EXPECT_EQ(labels.MatchablePairs(options).size(), 1u);
}

TEST(PairLabels, OverlapOrCommonTrack) {
  PairLabels labels({"a", "b", "c"}, true, true);
  labels.SetOverlap("a", "b", 0.3);            // MO >= .25
  labels.SetCommonTrackRatio("b", "c", 0.16);  // CT >= .15
  labels.SetOverlap("a", "c", 0.1);
  labels.SetCommonTrackRatio("a", "c", 0.1);
  const PairLabelOptions options;
  EXPECT_TRUE(labels.IsMatchable("a", "b", options));
  EXPECT_TRUE(labels.IsMatchable("b", "c", options));
  EXPECT_FALSE(labels.IsMatchable("a", "c", options));
  EXPECT_THROW(labels.SetOverlap("a", "x", 1.0), Error);
}

TEST(PairLabels, CsvRoundTrip) {
  const TemporaryDirectory dir;
  PairLabels labels = MakeLabels();
  labels.source = "hand-made";
  const std::string path = JoinPaths(dir.Path(), "labels.csv");
  labels.Write(path);
  const PairLabels read = PairLabels::Read(path);
  EXPECT_EQ(read.source, "hand-made");
  EXPECT_EQ(read.ImageNames(), labels.ImageNames());
  EXPECT_FALSE(read.HasOverlap());
  EXPECT_TRUE(read.HasCommonTrackRatio());
  EXPECT_DOUBLE_EQ(read.Evidence("b", "c").common_track_ratio, 0.2);
  EXPECT_EQ(read.MatchablePairs({}), labels.MatchablePairs({}));
}

TEST(PairSetScore, HandMadeSets) {
  const PairLabels labels = MakeLabels();
  const PairLabelOptions options;
  // 4 distinct labelled pairs (ab twice, aa dropped): ab, cd matchable; ae
  // not; ad shares nothing (wrong). A pair with an unknown image is
  // counted but not labelled.
  const std::vector<ImageNamePair> pairs = {{"a", "b"},
                                            {"b", "a"},
                                            {"a", "a"},
                                            {"d", "c"},
                                            {"a", "e"},
                                            {"a", "d"},
                                            {"a", "z"}};
  const PairSetScore metrics = ComputeRetrievalMetrics(pairs, labels, options);
  EXPECT_EQ(metrics.num_pairs, 5u);
  EXPECT_EQ(metrics.num_labelled_pairs, 4u);
  EXPECT_EQ(metrics.num_matchable, 3u);
  EXPECT_EQ(metrics.num_true_positives, 2u);
  EXPECT_EQ(metrics.num_wrong_pairs, 1u);
  EXPECT_DOUBLE_EQ(metrics.precision, 0.5);
  EXPECT_DOUBLE_EQ(metrics.recall, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(metrics.f_measure, 2 * 0.5 * (2.0 / 3) / (0.5 + 2.0 / 3));

  // The oracle: exactly the matchable pairs.
  const PairSetScore oracle =
      ComputeRetrievalMetrics(labels.MatchablePairs(options), labels, options);
  EXPECT_DOUBLE_EQ(oracle.precision, 1.0);
  EXPECT_DOUBLE_EQ(oracle.recall, 1.0);
  EXPECT_DOUBLE_EQ(oracle.f_measure, 1.0);
  EXPECT_EQ(oracle.num_wrong_pairs, 0u);

  const PairSetScore empty = ComputeRetrievalMetrics({}, labels, options);
  EXPECT_EQ(empty.precision, 0.0);
  EXPECT_EQ(empty.recall, 0.0);
  EXPECT_EQ(empty.f_measure, 0.0);
}

TEST(PairSetScore, AverageIsPerScene) {
  PairSetScore a, b;
  a.precision = 1.0;
  a.recall = 0.5;
  a.f_measure = FMeasure(1.0, 0.5);
  a.num_wrong_pairs = 2;
  b.precision = 0.5;
  b.recall = 1.0;
  b.f_measure = FMeasure(0.5, 1.0);
  b.num_wrong_pairs = 3;
  const PairSetScore mean = AverageRetrievalMetrics({a, b});
  EXPECT_DOUBLE_EQ(mean.precision, 0.75);
  EXPECT_DOUBLE_EQ(mean.recall, 0.75);
  EXPECT_DOUBLE_EQ(mean.f_measure, FMeasure(1.0, 0.5));
  EXPECT_EQ(mean.num_wrong_pairs, 5u);
}

TEST(BenchmarkMethod, ParsesSpecsAndCapsK) {
  const auto methods =
      ParseBenchmarkMethods("exhaustive, knn:25,vocab_tree:5,gcn,oracle");
  ASSERT_EQ(methods.size(), 5u);
  EXPECT_EQ(methods[1].pairing, "knn");
  EXPECT_EQ(methods[1].k, 25);
  EXPECT_EQ(methods[1].DirName(), "knn-25");
  EXPECT_EQ(methods[1].EffectiveK(11), 10);
  EXPECT_EQ(methods[1].EffectiveK(100), 25);
  EXPECT_TRUE(methods[4].IsOracle());
  EXPECT_EQ(methods[3].k, 0);
  // A user's pairs file is not a method: the oracle imports the labels.
  EXPECT_THROW(ParseBenchmarkMethod("imported"), Error);
  EXPECT_THROW(ParseBenchmarkMethod("knn"), Error);
  EXPECT_THROW(ParseBenchmarkMethod("knn:0"), Error);
  EXPECT_THROW(ParseBenchmarkMethod("exhaustive:3"), Error);
  EXPECT_THROW(ParseBenchmarkMethods("knn:5,knn:5"), Error);
  EXPECT_THROW(ParseBenchmarkMethods(" , "), Error);
  // "none": features and labels only.
  EXPECT_TRUE(ParseBenchmarkMethods(" none ").empty());
}

TEST(BenchmarkReport, PreparedScenesOnlyWithoutMethods) {
  BenchmarkResults results;
  SceneResult scene;
  scene.name = "synth-ordinary-80-s1";
  scene.kind = "synthetic";
  scene.label_source = "synthetic overlap";
  scene.num_images = 80;
  scene.num_labelled_images = 80;
  scene.num_matchable_pairs = 1205;
  results.scenes.push_back(scene);
  const std::string report = FormatBenchmarkReport(results);
  EXPECT_NE(report.find("--methods none"), std::string::npos) << report;
  EXPECT_NE(report.find("## synth-ordinary-80-s1"), std::string::npos);
  EXPECT_NE(report.find("1205 matchable pairs"), std::string::npos);
  EXPECT_EQ(report.find("Average over scenes"), std::string::npos);
  EXPECT_EQ(report.find("| method |"), std::string::npos) << report;
}

}  // namespace
}  // namespace colmap_gcn
