#include "evaluation/figures.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "util/error.h"

namespace colmap_gcn {
namespace {

void WritePng(const std::string& path, const cv::Mat& image) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, image);
  } catch (const cv::Exception& error) {
    ThrowError("cannot write ", path, ": ", error.what());
  }
  if (!ok) ThrowError("cannot write ", path);
}

std::pair<std::string, std::string> Ordered(const ImageNamePair& pair) {
  return pair.first < pair.second ? pair
                                  : ImageNamePair(pair.second, pair.first);
}

const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kBlack(0, 0, 0);
// BGR.
const cv::Scalar kGreen(60, 170, 40);
const cv::Scalar kOlive(40, 150, 170);
const cv::Scalar kRed(40, 40, 220);
const cv::Scalar kLightGrey(215, 215, 215);
const cv::Scalar kDarkGrey(90, 90, 90);

}  // namespace

void WriteViewGraphImage(const std::string& path,
                         const std::vector<std::string>& image_names,
                         const std::vector<ImageNamePair>& attempted,
                         const std::vector<ImageNamePair>& verified,
                         const PairLabels& labels,
                         const PairLabelOptions& label_options) {
  const int n = static_cast<int>(image_names.size());
  // At least ~600 px wide so small scenes stay readable; at least 1 px per
  // image for large ones.
  const int cell = std::max(1, 600 / std::max(1, n));
  const int margin = 20;
  const int size = n * cell;
  cv::Mat image(size + 2 * margin, size + 2 * margin, CV_8UC3, kWhite);
  std::map<std::string, int> index;
  for (int i = 0; i < n; ++i) index[image_names[i]] = i;
  const auto fill = [&](int row, int col, const cv::Scalar& colour) {
    cv::rectangle(
        image,
        cv::Rect(margin + col * cell, margin + row * cell, cell, cell),
        colour,
        cv::FILLED);
  };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < i; ++j) {
      if (labels.IsMatchable(image_names[i], image_names[j], label_options)) {
        fill(i, j, kDarkGrey);
      }
    }
  }
  std::set<ImageNamePair> verified_set;
  for (const auto& pair : verified) verified_set.insert(Ordered(pair));
  for (const auto& pair : attempted) {
    const ImageNamePair ordered = Ordered(pair);
    const auto a = index.find(ordered.first);
    const auto b = index.find(ordered.second);
    if (a == index.end() || b == index.end() || a->second == b->second) {
      continue;
    }
    const int row = std::min(a->second, b->second);
    const int col = std::max(a->second, b->second);
    cv::Scalar colour = kLightGrey;
    if (verified_set.count(ordered) > 0) {
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
    fill(row, col, colour);
  }
  cv::rectangle(
      image, cv::Rect(margin - 1, margin - 1, size + 2, size + 2), kBlack, 1);
  cv::line(image,
           cv::Point(margin, margin),
           cv::Point(margin + size, margin + size),
           kBlack,
           1);
  WritePng(path, image);
}

void WritePrecisionRecallPlot(
    const std::string& path,
    const std::string& title,
    const std::vector<PrecisionRecallSeries>& series,
    const std::vector<std::pair<std::string, std::pair<double, double>>>&
        references) {
  const int width = 700;
  const int height = 420;
  const int left = 60, right = 230, top = 40, bottom = 50;
  cv::Mat image(height, width, CV_8UC3, kWhite);
  const int plot_w = width - left - right;
  const int plot_h = height - top - bottom;
  int max_k = 1;
  for (const auto& s : series) {
    for (int k : s.k) max_k = std::max(max_k, k);
  }
  // log-scaled k axis: the paper's k values span 5..100.
  const double log_max = std::log(static_cast<double>(max_k) + 1.0);
  const auto x_of = [&](int k) {
    return left +
           static_cast<int>(std::lround(
               plot_w * std::log(static_cast<double>(k) + 1.0) / log_max));
  };
  const auto y_of = [&](double v) {
    return top + static_cast<int>(std::lround(plot_h * (1.0 - v)));
  };
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  cv::putText(
      image, title, cv::Point(left, 25), font, 0.55, kBlack, 1, cv::LINE_AA);
  cv::rectangle(image, cv::Rect(left, top, plot_w, plot_h), kBlack, 1);
  for (int t = 0; t <= 4; ++t) {
    const double v = t / 4.0;
    cv::line(image,
             cv::Point(left, y_of(v)),
             cv::Point(left + plot_w, y_of(v)),
             kLightGrey,
             1);
    char label[16];
    std::snprintf(label, sizeof(label), "%.2f", v);
    cv::putText(image,
                label,
                cv::Point(10, y_of(v) + 5),
                font,
                0.4,
                kBlack,
                1,
                cv::LINE_AA);
  }
  std::set<int> ticks;
  for (const auto& s : series) ticks.insert(s.k.begin(), s.k.end());
  for (int k : ticks) {
    cv::putText(image,
                std::to_string(k),
                cv::Point(x_of(k) - 8, top + plot_h + 18),
                font,
                0.4,
                kBlack,
                1,
                cv::LINE_AA);
  }
  cv::putText(image,
              "k (log scale)",
              cv::Point(left + plot_w / 2 - 40, height - 12),
              font,
              0.45,
              kBlack,
              1,
              cv::LINE_AA);
  const std::vector<cv::Scalar> colours = {cv::Scalar(180, 100, 30),
                                           cv::Scalar(30, 120, 230),
                                           cv::Scalar(60, 160, 60),
                                           cv::Scalar(150, 60, 150),
                                           cv::Scalar(40, 40, 200)};
  int legend_y = top + 10;
  const auto legend =
      [&](const std::string& text, const cv::Scalar& colour, bool dashed) {
        const int x0 = left + plot_w + 12;
        if (dashed) {
          for (int x = x0; x < x0 + 24; x += 8) {
            cv::line(image,
                     cv::Point(x, legend_y),
                     cv::Point(x + 4, legend_y),
                     colour,
                     2);
          }
        } else {
          cv::line(image,
                   cv::Point(x0, legend_y),
                   cv::Point(x0 + 24, legend_y),
                   colour,
                   2);
        }
        cv::putText(image,
                    text,
                    cv::Point(x0 + 30, legend_y + 4),
                    font,
                    0.4,
                    kBlack,
                    1,
                    cv::LINE_AA);
        legend_y += 18;
      };
  const auto dashed_line =
      [&](cv::Point a, cv::Point b, const cv::Scalar& colour) {
        const double length = std::hypot(b.x - a.x, b.y - a.y);
        const int steps = std::max(1, static_cast<int>(length / 6));
        for (int s = 0; s < steps; s += 2) {
          const double t0 = static_cast<double>(s) / steps;
          const double t1 = std::min(1.0, static_cast<double>(s + 1) / steps);
          cv::line(image,
                   cv::Point(a.x + (b.x - a.x) * t0, a.y + (b.y - a.y) * t0),
                   cv::Point(a.x + (b.x - a.x) * t1, a.y + (b.y - a.y) * t1),
                   colour,
                   2);
        }
      };
  size_t colour_idx = 0;
  for (const auto& s : series) {
    const cv::Scalar colour = colours[colour_idx++ % colours.size()];
    for (size_t i = 0; i < s.k.size(); ++i) {
      const cv::Point p(x_of(s.k[i]), y_of(s.precision[i]));
      const cv::Point r(x_of(s.k[i]), y_of(s.recall[i]));
      cv::circle(image, p, 3, colour, cv::FILLED);
      cv::circle(image, r, 3, colour, 1);
      if (i > 0) {
        cv::line(image,
                 cv::Point(x_of(s.k[i - 1]), y_of(s.precision[i - 1])),
                 p,
                 colour,
                 2,
                 cv::LINE_AA);
        dashed_line(
            cv::Point(x_of(s.k[i - 1]), y_of(s.recall[i - 1])), r, colour);
      }
    }
    legend(s.name + " precision", colour, false);
    legend(s.name + " recall", colour, true);
  }
  for (const auto& [name, values] : references) {
    const cv::Scalar colour = colours[colour_idx++ % colours.size()];
    cv::line(image,
             cv::Point(left, y_of(values.first)),
             cv::Point(left + plot_w, y_of(values.first)),
             colour,
             1);
    dashed_line(cv::Point(left, y_of(values.second)),
                cv::Point(left + plot_w, y_of(values.second)),
                colour);
    legend(name + " precision", colour, false);
    legend(name + " recall", colour, true);
  }
  WritePng(path, image);
}

}  // namespace colmap_gcn
