#include "evaluation/figures.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <opencv2/imgproc.hpp>

#include "evaluation/figure_drawing.h"
#include "util/error.h"

namespace colmap_gcn {
namespace {

using namespace figure;  // NOLINT: the drawing helpers and colours

std::pair<std::string, std::string> Ordered(const ImageNamePair& pair) {
  return pair.first < pair.second ? pair
                                  : ImageNamePair(pair.second, pair.first);
}

}  // namespace

void WriteViewGraphImage(const std::string& path,
                         const std::vector<std::string>& image_names,
                         const std::vector<ImageNamePair>& attempted,
                         const std::vector<ImageNamePair>& verified,
                         const std::vector<ImageNamePair>& hidden,
                         const PairLabels& labels,
                         const PairLabelOptions& label_options,
                         const std::string& title) {
  const int n = static_cast<int>(image_names.size());
  std::map<std::string, int> index;
  for (int i = 0; i < n; ++i) index[image_names[i]] = i;
  std::vector<std::tuple<int, int, cv::Scalar>> cells;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < i; ++j) {
      if (labels.IsMatchable(image_names[i], image_names[j], label_options)) {
        cells.emplace_back(i, j, kDarkGrey);
      }
    }
  }
  std::set<ImageNamePair> verified_set;
  for (const auto& pair : verified) verified_set.insert(Ordered(pair));
  std::set<ImageNamePair> hidden_set;
  for (const auto& pair : hidden) hidden_set.insert(Ordered(pair));
  size_t num_attempted = 0, num_verified = 0, num_hidden = 0;
  for (const auto& pair : attempted) {
    const ImageNamePair ordered = Ordered(pair);
    const auto a = index.find(ordered.first);
    const auto b = index.find(ordered.second);
    if (a == index.end() || b == index.end() || a->second == b->second) {
      continue;
    }
    ++num_attempted;
    const int row = std::min(a->second, b->second);
    const int col = std::max(a->second, b->second);
    cv::Scalar colour = kLightGrey;
    if (hidden_set.count(ordered) > 0) {
      ++num_hidden;
      colour = kPurple;
    } else if (verified_set.count(ordered) > 0) {
      ++num_verified;
      if (labels.SharesNothing(ordered.first, ordered.second)) {
        colour = kRed;
      } else if (labels.IsMatchable(
                     ordered.first, ordered.second, label_options) ||
                 !labels.IsLabelled(ordered.first, ordered.second)) {
        colour = kGreen;
      } else {
        colour = kOlive;
      }
    }
    cells.emplace_back(row, col, colour);
  }
  constexpr int kSide = 560, kLeft = 90, kTop = 90, kWidth = 800;
  cv::Mat image(kTop + kSide + 150, kWidth, CV_8UC3, kWhite);
  Text(&image,
       title.empty() ? "View graph" : title,
       cv::Point(20, 30),
       0.65,
       kBlack,
       2);
  Text(&image,
       std::to_string(n) + " images; above the diagonal: the " +
           std::to_string(num_attempted) + " pairs matched (" +
           std::to_string(num_verified) + " verified" +
           (num_hidden > 0
                ? ", " + std::to_string(num_hidden) + " hidden as look-alikes"
                : std::string()) +
           ")",
       cv::Point(20, 55),
       0.45,
       kDarkGrey);
  Text(&image,
       "below the diagonal: the pairs the ground truth calls matchable",
       cv::Point(20, 75),
       0.45,
       kDarkGrey);
  DrawMatrix(&image,
             cv::Rect(kLeft, kTop, kSide, kSide),
             n,
             cells,
             "image number (name order)",
             "image number (name order)");
  DrawLegend(&image,
             cv::Point(kLeft, kTop + kSide + 55),
             kWidth - kLeft - 20,
             {{kGreen, "verified, matchable"},
              {kOlive, "verified, below the label thresholds"},
              {kRed, "verified, images share nothing (wrong)"},
              {kLightGrey, "matched, rejected by verification"},
              {kPurple, "verified, hidden as a look-alike"},
              {kDarkGrey, "matchable by the ground truth"},
              {kWhite, "not matched / not matchable"}});
  WritePng(path, image);
}

namespace {

// A [0, 1]-valued line chart: frame, grid, x ticks, legend on the right.
class LineChart {
 public:
  LineChart(const std::string& title,
            const std::string& x_label,
            const std::string& y_label,
            const std::vector<double>& x_ticks,
            bool log_x)
      : image_(kHeight, kWidth, CV_8UC3, kWhite), log_x_(log_x) {
    for (const double x : x_ticks) {
      x_min_ = std::min(x_min_, x);
      x_max_ = std::max(x_max_, x);
    }
    if (log_x_) x_min_ = 0;
    if (!(x_max_ > x_min_)) x_max_ = x_min_ + 1;
    cv::putText(image_,
                title,
                cv::Point(kLeft, 25),
                kFont,
                0.55,
                kBlack,
                1,
                cv::LINE_AA);
    cv::rectangle(image_, cv::Rect(kLeft, kTop, PlotW(), PlotH()), kBlack, 1);
    for (int t = 0; t <= 4; ++t) {
      const double v = t / 4.0;
      cv::line(image_, Pt(x_min_, v), Pt(x_max_, v), kLightGrey, 1);
      char label[16];
      std::snprintf(label, sizeof(label), "%.2f", v);
      Text(label, cv::Point(32, Pt(x_min_, v).y + 5));
    }
    for (const double x : x_ticks) {
      char label[16];
      std::snprintf(label, sizeof(label), "%g", x);
      Text(label, cv::Point(Pt(x, 0).x - 8, kTop + PlotH() + 18));
    }
    Text(x_label, cv::Point(kLeft + PlotW() / 2 - 40, kHeight - 12), 0.45);
    VerticalText(&image_,
                 y_label,
                 cv::Point(6, kTop + PlotH() / 2 + TextWidth(y_label) / 2));
  }

  cv::Point Pt(double x, double y) const {
    const double fx = log_x_ ? std::log(x + 1.0) / std::log(x_max_ + 1.0)
                             : (x - x_min_) / (x_max_ - x_min_);
    return cv::Point(kLeft + static_cast<int>(std::lround(PlotW() * fx)),
                     kTop + static_cast<int>(std::lround(PlotH() * (1.0 - y))));
  }

  void Line(cv::Point a, cv::Point b, const cv::Scalar& colour, bool dashed) {
    DrawLine(&image_, a, b, colour, 2, dashed);
  }

  // A polyline with markers (filled for solid lines, open for dashed).
  void Series(const std::vector<double>& x,
              const std::vector<double>& y,
              const cv::Scalar& colour,
              bool dashed) {
    for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
      cv::circle(image_, Pt(x[i], y[i]), 3, colour, dashed ? 1 : cv::FILLED);
      if (i > 0) Line(Pt(x[i - 1], y[i - 1]), Pt(x[i], y[i]), colour, dashed);
    }
  }

  void Legend(const std::string& text, const cv::Scalar& colour, bool dashed) {
    const int x0 = kLeft + PlotW() + 12;
    Line(cv::Point(x0, legend_y_),
         cv::Point(x0 + 24, legend_y_),
         colour,
         dashed);
    Text(text, cv::Point(x0 + 30, legend_y_ + 4));
    legend_y_ += 18;
  }

  void Write(const std::string& path) const { WritePng(path, image_); }

  static cv::Scalar Colour(size_t i) {
    static const std::vector<cv::Scalar> kColours = {cv::Scalar(180, 100, 30),
                                                     cv::Scalar(30, 120, 230),
                                                     cv::Scalar(60, 160, 60),
                                                     cv::Scalar(150, 60, 150),
                                                     cv::Scalar(40, 40, 200)};
    return kColours[i % kColours.size()];
  }

 private:
  static constexpr int kWidth = 700, kHeight = 420;
  static constexpr int kLeft = 80, kRight = 230, kTop = 40, kBottom = 50;
  static constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
  static int PlotW() { return kWidth - kLeft - kRight; }
  static int PlotH() { return kHeight - kTop - kBottom; }
  void Text(const std::string& text, cv::Point at, double scale = 0.4) {
    cv::putText(image_, text, at, kFont, scale, kBlack, 1, cv::LINE_AA);
  }

  cv::Mat image_;
  bool log_x_;
  double x_min_ = 1e300, x_max_ = -1e300;
  int legend_y_ = kTop + 10;
};

}  // namespace

void WritePrecisionRecallPlot(
    const std::string& path,
    const std::string& title,
    const std::vector<PrecisionRecallSeries>& series,
    const std::vector<std::pair<std::string, std::pair<double, double>>>&
        references) {
  // log-scaled k axis: the paper's k values span 5..100.
  std::set<double> ticks;
  for (const auto& s : series) ticks.insert(s.k.begin(), s.k.end());
  if (ticks.empty()) ticks.insert(1);
  LineChart chart(title,
                  "k: pairs per image (log scale)",
                  "precision (solid), recall (dashed)",
                  {ticks.begin(), ticks.end()},
                  /*log_x=*/true);
  size_t colour_idx = 0;
  for (const auto& s : series) {
    const cv::Scalar colour = LineChart::Colour(colour_idx++);
    const std::vector<double> k(s.k.begin(), s.k.end());
    chart.Series(k, s.precision, colour, false);
    chart.Series(k, s.recall, colour, true);
    chart.Legend(s.name + " precision", colour, false);
    chart.Legend(s.name + " recall", colour, true);
  }
  const double x_max = *ticks.rbegin();
  for (const auto& [name, values] : references) {
    const cv::Scalar colour = LineChart::Colour(colour_idx++);
    chart.Line(chart.Pt(0, values.first),
               chart.Pt(x_max, values.first),
               colour,
               false);
    chart.Line(chart.Pt(0, values.second),
               chart.Pt(x_max, values.second),
               colour,
               true);
    chart.Legend(name + " precision", colour, false);
    chart.Legend(name + " recall", colour, true);
  }
  chart.Write(path);
}

void WriteLinePlot(const std::string& path,
                   const std::string& title,
                   const std::string& x_label,
                   const std::vector<double>& x,
                   const std::vector<LinePlotSeries>& series,
                   const std::string& y_label) {
  LineChart chart(title, x_label, y_label, x, /*log_x=*/false);
  for (size_t i = 0; i < series.size(); ++i) {
    const cv::Scalar colour = LineChart::Colour(i);
    chart.Series(x, series[i].y, colour, series[i].dashed);
    chart.Legend(series[i].name, colour, series[i].dashed);
  }
  chart.Write(path);
}

}  // namespace colmap_gcn
