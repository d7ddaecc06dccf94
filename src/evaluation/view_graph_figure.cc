#include "evaluation/view_graph_figure.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>

#include <opencv2/imgproc.hpp>

#include "evaluation/figure_drawing.h"
#include "scene/database_copy.h"
#include "scene/two_view_geometry_store.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using figure::Key;
using figure::LegendEntry;

ImageNamePair Ordered(const ImageNamePair& pair) {
  return pair.first < pair.second ? pair
                                  : ImageNamePair(pair.second, pair.first);
}

// Appends the pair's image names, ordered; a pair of an unknown id is
// skipped.
void AppendNamedPair(const std::map<image_t, std::string>& names,
                     const image_pair_t pair_id,
                     std::vector<ImageNamePair>* pairs) {
  const ImagePair ids = PairIdToImagePair(pair_id);
  const auto a = names.find(ids.first);
  const auto b = names.find(ids.second);
  if (a == names.end() || b == names.end()) return;
  pairs->push_back(Ordered({a->second, b->second}));
}

// Index pairs (i < j) of the named pairs whose images are both known.
std::vector<std::pair<size_t, size_t>> IndexPairs(
    const std::vector<ImageNamePair>& pairs,
    const std::map<std::string, size_t>& index) {
  std::vector<std::pair<size_t, size_t>> result;
  for (const ImageNamePair& pair : pairs) {
    const auto a = index.find(pair.first);
    const auto b = index.find(pair.second);
    if (a == index.end() || b == index.end() || a->second == b->second) {
      continue;
    }
    result.emplace_back(std::min(a->second, b->second),
                        std::max(a->second, b->second));
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

constexpr int kWidth = 1240;
constexpr int kPanel = 520;  // side of each of the two panels
constexpr int kPanelTop = 100;
constexpr int kMatrixLeft = 90;
constexpr int kLayoutLeft = 680;

void DrawLayout(cv::Mat* image,
                const MatchedViewGraph& graph,
                const std::vector<std::pair<size_t, size_t>>& verified,
                const std::vector<std::pair<size_t, size_t>>& hidden,
                const std::vector<std::pair<size_t, size_t>>& rejected) {
  const size_t n = graph.image_names.size();
  const std::vector<std::pair<double, double>> positions =
      ForceDirectedLayout(n, verified);
  const cv::Rect area(kLayoutLeft, kPanelTop, kPanel, kPanel);
  cv::rectangle(*image, area, figure::kLightGrey, 1);
  const int pad = 24;
  const auto point = [&](size_t i) {
    return cv::Point(area.x + pad +
                         static_cast<int>(std::lround(positions[i].first *
                                                      (kPanel - 2 * pad))),
                     area.y + pad +
                         static_cast<int>(std::lround(positions[i].second *
                                                      (kPanel - 2 * pad))));
  };
  for (const auto& [a, b] : rejected) {
    figure::DrawLine(image, point(a), point(b), figure::kLightRed, 1, true);
  }
  for (const auto& [a, b] : hidden) {
    figure::DrawLine(image, point(a), point(b), figure::kPurple, 1, true);
  }
  for (const auto& [a, b] : verified) {
    figure::DrawLine(image, point(a), point(b), figure::kGreen, 2, false);
  }
  const int radius = std::clamp(
      static_cast<int>(60 / std::sqrt(std::max<size_t>(1, n))), 3, 8);
  for (size_t i = 0; i < n; ++i) {
    const bool unregistered = graph.registration_known &&
                              graph.registered.count(graph.image_names[i]) == 0;
    if (unregistered) {
      cv::circle(*image, point(i), radius + 1, figure::kWhite, cv::FILLED);
      cv::circle(*image, point(i), radius + 1, figure::kRed, 2, cv::LINE_AA);
    } else {
      cv::circle(
          *image, point(i), radius, figure::kBlue, cv::FILLED, cv::LINE_AA);
    }
    if (n <= 50) {
      figure::Text(image,
                   std::to_string(i),
                   point(i) + cv::Point(radius + 1, -radius - 1),
                   0.38,
                   figure::kDarkGrey);
    }
  }
}

}  // namespace

std::vector<std::pair<double, double>> ForceDirectedLayout(
    const size_t num_nodes,
    const std::vector<std::pair<size_t, size_t>>& edges) {
  const size_t n = num_nodes;
  std::vector<double> x(n), y(n);
  const double kPi = 3.14159265358979323846;
  for (size_t i = 0; i < n; ++i) {
    x[i] = 0.5 + 0.4 * std::cos(2 * kPi * i / std::max<size_t>(1, n));
    y[i] = 0.5 + 0.4 * std::sin(2 * kPi * i / std::max<size_t>(1, n));
  }
  if (n == 0) return {};
  if (n == 1) return {{0.5, 0.5}};
  // Fruchterman-Reingold in the unit square, with a weak pull to the centre
  // so that separate components stay in view.
  const double k = std::sqrt(1.0 / n);
  const int iterations = n > 500 ? 60 : 200;
  std::vector<double> dx(n), dy(n);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    std::fill(dx.begin(), dx.end(), 0.0);
    std::fill(dy.begin(), dy.end(), 0.0);
    for (size_t i = 0; i < n; ++i) {
      for (size_t j = i + 1; j < n; ++j) {
        const double ex = x[i] - x[j], ey = y[i] - y[j];
        const double d2 = std::max(ex * ex + ey * ey, 1e-9);
        const double f = k * k / d2;  // repulsion / distance
        dx[i] += ex * f, dy[i] += ey * f;
        dx[j] -= ex * f, dy[j] -= ey * f;
      }
    }
    for (const auto& [a, b] : edges) {
      const double ex = x[a] - x[b], ey = y[a] - y[b];
      const double d = std::sqrt(ex * ex + ey * ey);
      const double f = d / k;  // attraction / distance
      dx[a] -= ex * f, dy[a] -= ey * f;
      dx[b] += ex * f, dy[b] += ey * f;
    }
    const double temperature =
        0.1 * (1.0 - static_cast<double>(iteration) / iterations) + 0.002;
    for (size_t i = 0; i < n; ++i) {
      dx[i] += (0.5 - x[i]) * 0.5 * k, dy[i] += (0.5 - y[i]) * 0.5 * k;
      const double d = std::max(std::hypot(dx[i], dy[i]), 1e-12);
      const double step = std::min(d, temperature);
      x[i] += dx[i] / d * step;
      y[i] += dy[i] / d * step;
    }
  }
  // Fit to [0, 1]^2, keeping the aspect ratio.
  const auto [x_min, x_max] = std::minmax_element(x.begin(), x.end());
  const auto [y_min, y_max] = std::minmax_element(y.begin(), y.end());
  const double span = std::max({*x_max - *x_min, *y_max - *y_min, 1e-9});
  const double x0 = *x_min - (span - (*x_max - *x_min)) / 2;
  const double y0 = *y_min - (span - (*y_max - *y_min)) / 2;
  std::vector<std::pair<double, double>> positions(n);
  for (size_t i = 0; i < n; ++i) {
    positions[i] = {(x[i] - x0) / span, (y[i] - y0) / span};
  }
  return positions;
}

void WriteMatchedViewGraphImage(const std::string& path,
                                const MatchedViewGraph& graph) {
  const size_t n = graph.image_names.size();
  std::map<std::string, size_t> index;
  for (size_t i = 0; i < n; ++i) index[graph.image_names[i]] = i;
  const auto attempted = IndexPairs(graph.attempted, index);
  const auto verified = IndexPairs(graph.verified, index);
  const auto hidden = IndexPairs(graph.hidden, index);
  std::vector<std::pair<size_t, size_t>> kept, rejected;
  std::set_union(verified.begin(),
                 verified.end(),
                 hidden.begin(),
                 hidden.end(),
                 std::back_inserter(kept));
  std::set_difference(attempted.begin(),
                      attempted.end(),
                      kept.begin(),
                      kept.end(),
                      std::back_inserter(rejected));

  cv::Mat image(760, kWidth, CV_8UC3, figure::kWhite);
  figure::Text(&image, graph.title, cv::Point(20, 32), 0.7, figure::kBlack, 2);
  const std::string counts =
      std::to_string(n) + " images, " + std::to_string(n * (n - 1) / 2) +
      " possible pairs; " + std::to_string(attempted.size()) +
      " pairs matched, " + std::to_string(verified.size()) + " verified, " +
      std::to_string(rejected.size()) + " rejected" +
      (hidden.empty()
           ? std::string()
           : ", " + std::to_string(hidden.size()) + " hidden as look-alikes");
  figure::Text(&image, counts, cv::Point(20, 58), 0.5, figure::kDarkGrey);
  figure::Text(
      &image, "Which pairs were matched", cv::Point(kMatrixLeft, 88), 0.5);
  figure::Text(&image,
               "Images placed so that verified pairs are close",
               cv::Point(kLayoutLeft, 88),
               0.5);

  std::vector<std::tuple<int, int, cv::Scalar>> cells;
  for (const auto& [a, b] : rejected) {
    cells.emplace_back(a, b, figure::kRed);
    cells.emplace_back(b, a, figure::kRed);
  }
  for (const auto& [a, b] : verified) {
    cells.emplace_back(a, b, figure::kGreen);
    cells.emplace_back(b, a, figure::kGreen);
  }
  for (const auto& [a, b] : hidden) {
    cells.emplace_back(a, b, figure::kPurple);
    cells.emplace_back(b, a, figure::kPurple);
  }
  figure::DrawMatrix(&image,
                     cv::Rect(kMatrixLeft, kPanelTop, kPanel, kPanel),
                     static_cast<int>(n),
                     cells,
                     "image number (name order)",
                     "image number (name order)");
  DrawLayout(&image, graph, verified, hidden, rejected);

  std::vector<LegendEntry> legend = {
      {figure::kGreen, "verified pair (two-view geometry confirmed)"},
      {figure::kRed, "matched but rejected by verification"},
      {figure::kWhite, "not matched (skipped)"},
      {figure::kGreen, "verified pair", Key::kLine},
      {figure::kLightRed, "rejected pair", Key::kDashedLine}};
  if (!hidden.empty()) {
    legend.insert(
        legend.begin() + 2,
        {figure::kPurple, "verified, hidden from the mapper as a look-alike"});
    legend.push_back({figure::kPurple, "look-alike pair", Key::kDashedLine});
  }
  if (graph.registration_known) {
    legend.push_back({figure::kBlue, "registered image", Key::kDot});
    legend.push_back({figure::kRed, "image not registered", Key::kRing});
  } else {
    legend.push_back({figure::kBlue, "image (number: name order)", Key::kDot});
  }
  figure::DrawLegend(&image,
                     cv::Point(kMatrixLeft, kPanelTop + kPanel + 60),
                     kWidth - kMatrixLeft - 20,
                     legend);
  figure::WritePng(path, image);
}

std::vector<ImageNamePair> ReadVerifiedImagePairs(
    const Database& database, const size_t min_num_inliers) {
  std::map<image_t, std::string> names;
  for (const DatabaseImage& image : database.ReadAllImages()) {
    names[image.image_id] = image.name;
  }
  std::vector<ImageNamePair> verified;
  for (const TwoViewGeometryInfo& info : database.ReadTwoViewGeometryInfos()) {
    if (!IsVerifiedTwoViewGeometry(
            info.config, info.num_inliers, min_num_inliers)) {
      continue;
    }
    AppendNamedPair(names, info.pair_id, &verified);
  }
  return verified;
}

MatchedViewGraph ReadMatchedViewGraph(const std::string& database_path,
                                      const std::string& pairs_path,
                                      const size_t min_num_inliers) {
  MatchedViewGraph graph;
  {
    const TwoViewGeometryStore database(database_path);
    graph.image_names = ReadImageNamesSorted(database);
    graph.verified = ReadVerifiedImagePairs(database, min_num_inliers);
    graph.hidden = ReadHiddenImagePairs(database, min_num_inliers);
  }
  // A reader of a WAL database leaves an empty "-wal" and "-shm" beside it.
  RemoveEmptySqliteSideFiles(database_path);
  if (!pairs_path.empty() && ExistsFile(pairs_path)) {
    graph.attempted = ReadPairsFile(pairs_path);
  }
  return graph;
}

std::vector<ImageNamePair> ReadHiddenImagePairs(
    const std::string& database_path, const size_t min_num_inliers) {
  return ReadHiddenImagePairs(TwoViewGeometryStore(database_path),
                              min_num_inliers);
}

std::vector<ImageNamePair> ReadHiddenImagePairs(
    const TwoViewGeometryStore& database, const size_t min_num_inliers) {
  std::map<image_t, std::string> names;
  for (const DatabaseImage& image : database.ReadAllImages()) {
    names[image.image_id] = image.name;
  }
  std::vector<ImageNamePair> hidden;
  for (const HiddenTwoViewGeometry& pair : database.ReadHiddenPairs()) {
    // The side table keeps inlier counts, not configurations: a hidden pair
    // was verified, so only its count is checked.
    if (!IsVerifiedTwoViewGeometry(2, pair.num_inliers, min_num_inliers)) {
      continue;
    }
    AppendNamedPair(names, pair.pair_id, &hidden);
  }
  return hidden;
}

std::vector<std::string> ReadImageNamesSorted(const Database& database) {
  std::vector<std::string> names;
  for (const DatabaseImage& image : database.ReadAllImages()) {
    names.push_back(image.name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace colmap_gcn
