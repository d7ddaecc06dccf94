#pragma once

#include <string>
#include <tuple>
#include <vector>

#include <opencv2/core.hpp>

namespace colmap_gcn {
namespace figure {

// Colours (BGR) shared by the figures.
const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGreen(60, 170, 40);
const cv::Scalar kOlive(40, 150, 170);
const cv::Scalar kRed(40, 40, 220);
const cv::Scalar kLightRed(150, 150, 245);
const cv::Scalar kLightGrey(215, 215, 215);
const cv::Scalar kDarkGrey(90, 90, 90);
const cv::Scalar kBlue(180, 100, 30);
// Pairs the look-alike filter hid from the mapper.
const cv::Scalar kPurple(160, 50, 150);

// Writes a PNG; throws Error naming the path if it cannot.
void WritePng(const std::string& path, const cv::Mat& image);

// Anti-aliased text with its baseline's left end at `at`.
void Text(cv::Mat* image,
          const std::string& text,
          cv::Point at,
          double scale = 0.45,
          const cv::Scalar& colour = kBlack,
          int thickness = 1);

// Text rotated by 90 degrees (read bottom to top) in a box whose
// bottom-left corner is `bottom_left`.
void VerticalText(cv::Mat* image,
                  const std::string& text,
                  cv::Point bottom_left,
                  double scale = 0.45);

// Width in pixels of Text(text, scale).
int TextWidth(const std::string& text, double scale = 0.45);

// How a legend entry's key is drawn.
enum class Key { kSquare, kDot, kRing, kLine, kDashedLine };
struct LegendEntry {
  cv::Scalar colour;
  std::string text;
  Key key = Key::kSquare;
};

// Entries left to right from `top_left`, wrapped at `max_width`; returns
// the y below the last row.
int DrawLegend(cv::Mat* image,
               cv::Point top_left,
               int max_width,
               const std::vector<LegendEntry>& entries);

// A straight line, dashed or not.
void DrawLine(cv::Mat* image,
              cv::Point a,
              cv::Point b,
              const cv::Scalar& colour,
              int thickness,
              bool dashed);

// An n x n matrix image in `area` (a square): cells (row, col, colour),
// white elsewhere, a frame, the diagonal, index ticks on both axes and the
// axis labels (x below, y rotated on the left).
void DrawMatrix(cv::Mat* image,
                cv::Rect area,
                int n,
                const std::vector<std::tuple<int, int, cv::Scalar>>& cells,
                const std::string& x_label,
                const std::string& y_label);

// Tick step for an axis of n items: 1, 2, 5, 10, 20, 50, ... so that at
// most about max_ticks ticks are drawn.
int TickStep(int n, int max_ticks);

}  // namespace figure
}  // namespace colmap_gcn
