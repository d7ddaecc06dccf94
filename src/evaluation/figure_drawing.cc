#include "evaluation/figure_drawing.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "util/error.h"

namespace colmap_gcn {
namespace figure {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

}  // namespace

void WritePng(const std::string& path, const cv::Mat& image) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, image);
  } catch (const cv::Exception& error) {
    ThrowError("cannot write ", path, ": ", error.what());
  }
  if (!ok) ThrowError("cannot write ", path);
}

void Text(cv::Mat* image,
          const std::string& text,
          const cv::Point at,
          const double scale,
          const cv::Scalar& colour,
          const int thickness) {
  cv::putText(*image, text, at, kFont, scale, colour, thickness, cv::LINE_AA);
}

int TextWidth(const std::string& text, const double scale) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, 1, &baseline).width;
}

void VerticalText(cv::Mat* image,
                  const std::string& text,
                  const cv::Point bottom_left,
                  const double scale) {
  const int width = TextWidth(text, scale) + 4;
  const int height = static_cast<int>(std::lround(30 * scale)) + 6;
  cv::Mat strip(height, width, CV_8UC3, kWhite);
  Text(&strip, text, cv::Point(2, height - 6), scale);
  cv::Mat rotated;
  cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  // rotated: `height` wide, `width` tall; its bottom-left corner goes to
  // bottom_left.
  cv::Rect target(
      bottom_left.x, bottom_left.y - width, rotated.cols, rotated.rows);
  target &= cv::Rect(0, 0, image->cols, image->rows);
  if (target.area() == 0) return;
  rotated(cv::Rect(0, 0, target.width, target.height)).copyTo((*image)(target));
}

void DrawLine(cv::Mat* image,
              const cv::Point a,
              const cv::Point b,
              const cv::Scalar& colour,
              const int thickness,
              const bool dashed) {
  if (!dashed) {
    cv::line(*image, a, b, colour, thickness, cv::LINE_AA);
    return;
  }
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  const int steps = std::max(1, static_cast<int>(length / 6));
  for (int s = 0; s < steps; s += 2) {
    const double t0 = static_cast<double>(s) / steps;
    const double t1 = std::min(1.0, static_cast<double>(s + 1) / steps);
    cv::line(*image,
             cv::Point(a.x + (b.x - a.x) * t0, a.y + (b.y - a.y) * t0),
             cv::Point(a.x + (b.x - a.x) * t1, a.y + (b.y - a.y) * t1),
             colour,
             thickness,
             cv::LINE_AA);
  }
}

int DrawLegend(cv::Mat* image,
               const cv::Point top_left,
               const int max_width,
               const std::vector<LegendEntry>& entries) {
  constexpr int kKey = 14, kGap = 22, kRow = 22;
  int x = top_left.x;
  int y = top_left.y;
  for (const LegendEntry& entry : entries) {
    const int width = kKey + 6 + TextWidth(entry.text);
    if (x > top_left.x && x + width > top_left.x + max_width) {
      x = top_left.x;
      y += kRow;
    }
    const cv::Point centre(x + kKey / 2, y + kKey / 2);
    switch (entry.key) {
      case Key::kSquare:
        cv::rectangle(
            *image, cv::Rect(x, y, kKey, kKey), entry.colour, cv::FILLED);
        cv::rectangle(*image, cv::Rect(x, y, kKey, kKey), kDarkGrey, 1);
        break;
      case Key::kDot:
        cv::circle(*image, centre, 6, entry.colour, cv::FILLED, cv::LINE_AA);
        break;
      case Key::kRing:
        cv::circle(*image, centre, 5, entry.colour, 2, cv::LINE_AA);
        break;
      case Key::kLine:
      case Key::kDashedLine:
        DrawLine(image,
                 cv::Point(x - 4, centre.y),
                 cv::Point(x + kKey + 4, centre.y),
                 entry.colour,
                 2,
                 entry.key == Key::kDashedLine);
        break;
    }
    Text(image, entry.text, cv::Point(x + kKey + 6, y + kKey - 2));
    x += width + kGap;
  }
  return y + kRow;
}

int TickStep(const int n, const int max_ticks) {
  int step = 1;
  for (int scale = 1;; scale *= 10) {
    for (const int m : {1, 2, 5}) {
      step = m * scale;
      if (n / step <= max_ticks) return step;
    }
  }
}

void DrawMatrix(cv::Mat* image,
                const cv::Rect area,
                const int n,
                const std::vector<std::tuple<int, int, cv::Scalar>>& cells,
                const std::string& x_label,
                const std::string& y_label) {
  const double cell = static_cast<double>(area.width) / std::max(1, n);
  const auto at = [&](int index) {
    return static_cast<int>(std::lround(index * cell));
  };
  for (const auto& [row, col, colour] : cells) {
    const cv::Rect rect(area.x + at(col),
                        area.y + at(row),
                        std::max(1, at(col + 1) - at(col)),
                        std::max(1, at(row + 1) - at(row)));
    cv::rectangle(*image, rect, colour, cv::FILLED);
  }
  cv::rectangle(
      *image,
      cv::Rect(area.x - 1, area.y - 1, area.width + 2, area.height + 2),
      kBlack,
      1);
  cv::line(*image, area.tl(), area.br(), kLightGrey, 1);
  const int step = TickStep(n, 12);
  for (int i = 0; i < n; i += step) {
    const int offset = at(i) + static_cast<int>(cell / 2);
    const std::string label = std::to_string(i);
    // x axis (columns) below, y axis (rows) on the left.
    cv::line(*image,
             cv::Point(area.x + offset, area.br().y + 1),
             cv::Point(area.x + offset, area.br().y + 5),
             kBlack,
             1);
    Text(image,
         label,
         cv::Point(area.x + offset - TextWidth(label, 0.4) / 2,
                   area.br().y + 19),
         0.4);
    cv::line(*image,
             cv::Point(area.x - 5, area.y + offset),
             cv::Point(area.x - 1, area.y + offset),
             kBlack,
             1);
    Text(image,
         label,
         cv::Point(area.x - 8 - TextWidth(label, 0.4), area.y + offset + 4),
         0.4);
  }
  Text(image,
       x_label,
       cv::Point(area.x + area.width / 2 - TextWidth(x_label) / 2,
                 area.br().y + 40));
  VerticalText(image,
               y_label,
               cv::Point(area.x - 62,
                         area.y + area.height / 2 + TextWidth(y_label) / 2));
}

}  // namespace figure
}  // namespace colmap_gcn
