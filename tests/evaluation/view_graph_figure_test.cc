#include "evaluation/view_graph_figure.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "evaluation/figure_drawing.h"
#include "evaluation/figures.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

double Distance(const std::pair<double, double>& a,
                const std::pair<double, double>& b) {
  return std::hypot(a.first - b.first, a.second - b.second);
}

TEST(ForceDirectedLayout, IsDeterministicAndPullsVerifiedPairsTogether) {
  // Two chains of 6 images, each image linked to its successor.
  std::vector<std::pair<size_t, size_t>> edges;
  for (size_t i = 0; i + 1 < 6; ++i) edges.emplace_back(i, i + 1);
  for (size_t i = 6; i + 1 < 12; ++i) edges.emplace_back(i, i + 1);
  const auto layout = ForceDirectedLayout(12, edges);
  EXPECT_EQ(layout, ForceDirectedLayout(12, edges));
  ASSERT_EQ(layout.size(), 12u);
  double linked = 0.0, unlinked = 0.0;
  for (const auto& [a, b] : edges) linked += Distance(layout[a], layout[b]);
  for (size_t i = 0; i < 6; ++i) unlinked += Distance(layout[i], layout[i + 6]);
  EXPECT_LT(linked / edges.size(), unlinked / 6);
  for (const auto& [x, y] : layout) {
    EXPECT_GE(x, -1e-9);
    EXPECT_LE(x, 1 + 1e-9);
    EXPECT_GE(y, -1e-9);
    EXPECT_LE(y, 1 + 1e-9);
  }
  EXPECT_EQ(ForceDirectedLayout(1, {}).size(), 1u);
}

TEST(FigureDrawing, TickStepKeepsTheTicksFew) {
  EXPECT_EQ(figure::TickStep(8, 12), 1);
  EXPECT_EQ(figure::TickStep(24, 12), 2);
  EXPECT_EQ(figure::TickStep(48, 12), 5);
  EXPECT_EQ(figure::TickStep(1000, 12), 100);
}

// Counts the pixels of one BGR colour.
int CountColour(const cv::Mat& image, const cv::Scalar& colour) {
  cv::Mat mask;
  cv::inRange(image, colour, colour, mask);
  return cv::countNonZero(mask);
}

TEST(MatchedViewGraph, ShowsVerifiedRejectedAndUnregisteredImages) {
  TemporaryDirectory dir;
  MatchedViewGraph graph;
  graph.title = "test";
  graph.image_names = {"a", "b", "c", "d"};
  graph.attempted = {{"a", "b"}, {"b", "c"}, {"c", "d"}};
  graph.verified = {{"b", "a"}, {"b", "c"}};
  graph.registered = {"a", "b", "c"};
  graph.registration_known = true;
  const std::string path = JoinPaths(dir.Path(), "graph.png");
  WriteMatchedViewGraphImage(path, graph);
  const cv::Mat image = cv::imread(path);
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, 1240);
  // Green cells of the two verified pairs, red of the rejected one, and the
  // legend's keys of both.
  EXPECT_GT(CountColour(image, figure::kGreen), 2 * 130 * 130);
  EXPECT_GT(CountColour(image, figure::kRed), 2 * 120 * 120);
  EXPECT_GT(CountColour(image, figure::kBlue), 0);  // registered images
  // No look-alike hidden: no purple, not even in the legend.
  EXPECT_EQ(CountColour(image, figure::kPurple), 0);
}

TEST(MatchedViewGraph, ShowsLookalikesInTheirOwnColour) {
  TemporaryDirectory dir;
  MatchedViewGraph graph;
  graph.title = "test";
  graph.image_names = {"a", "b", "c", "d"};
  graph.attempted = {{"a", "b"}, {"b", "c"}, {"c", "d"}};
  graph.verified = {{"a", "b"}, {"b", "c"}};
  graph.hidden = {{"d", "c"}};
  const std::string path = JoinPaths(dir.Path(), "graph.png");
  WriteMatchedViewGraphImage(path, graph);
  const cv::Mat image = cv::imread(path);
  ASSERT_FALSE(image.empty());
  // The hidden pair's two cells are purple, not red: nothing was rejected.
  EXPECT_GT(CountColour(image, figure::kPurple), 2 * 120 * 120);
  EXPECT_LT(CountColour(image, figure::kRed), 120 * 120);
}

TEST(ViewGraphImage, HasTheLegendOfEveryColour) {
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "graph.png");
  WriteViewGraphImage(path,
                      {"a", "b", "c"},
                      {{"a", "b"}, {"b", "c"}},
                      {},
                      {{"c", "b"}},
                      PairLabels(),
                      PairLabelOptions(),
                      "scene / method");
  const cv::Mat image = cv::imread(path);
  ASSERT_FALSE(image.empty());
  // The rejected pair's cell and its legend key are light grey, the hidden
  // look-alike's purple; the olive key is drawn although no cell is olive.
  EXPECT_GT(CountColour(image, figure::kLightGrey), 180 * 180);
  EXPECT_GT(CountColour(image, figure::kPurple), 180 * 180);
  EXPECT_GT(CountColour(image, figure::kOlive), 100);
}

}  // namespace
}  // namespace colmap_gcn
