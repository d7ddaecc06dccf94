#include "synthetic/texture.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "synthetic/random.h"
#include "util/error.h"

namespace colmap_gcn {

Texture::Texture(const cv::Mat& bgr) {
  THROW_CHECK(bgr.type() == CV_8UC3 && !bgr.empty());
  levels_.push_back(bgr.isContinuous() ? bgr : bgr.clone());
  while (levels_.back().cols > 4 && levels_.back().rows > 4) {
    cv::Mat next;
    cv::pyrDown(levels_.back(), next);
    levels_.push_back(next);
  }
}

Eigen::Vector3f Texture::SampleLevel(int level, double u, double v) const {
  const cv::Mat& image = levels_[level];
  const int w = image.cols;
  const int h = image.rows;
  const double x = u * w - 0.5;
  const double y = v * h - 0.5;
  const double fx = std::floor(x);
  const double fy = std::floor(y);
  const float ax = static_cast<float>(x - fx);
  const float ay = static_cast<float>(y - fy);
  // Wrap-around addressing; fmod keeps huge coordinates in range.
  long x0 = static_cast<long>(fx - w * std::floor(fx / w));
  long y0 = static_cast<long>(fy - h * std::floor(fy / h));
  if (x0 >= w) x0 -= w;
  if (y0 >= h) y0 -= h;
  const long x1 = x0 + 1 == w ? 0 : x0 + 1;
  const long y1 = y0 + 1 == h ? 0 : y0 + 1;
  const uint8_t* row0 = image.ptr<uint8_t>(static_cast<int>(y0));
  const uint8_t* row1 = image.ptr<uint8_t>(static_cast<int>(y1));
  Eigen::Vector3f result;
  for (int c = 0; c < 3; ++c) {
    const float top = (1.0f - ax) * row0[3 * x0 + c] + ax * row0[3 * x1 + c];
    const float bottom = (1.0f - ax) * row1[3 * x0 + c] + ax * row1[3 * x1 + c];
    result(c) = (1.0f - ay) * top + ay * bottom;
  }
  return result;
}

Eigen::Vector3f Texture::Sample(double u, double v, double lod) const {
  const double max_level = static_cast<double>(levels_.size() - 1);
  lod = std::clamp(lod, 0.0, max_level);
  const int level0 = static_cast<int>(std::floor(lod));
  const float alpha = static_cast<float>(lod - level0);
  if (alpha < 1e-3f || level0 + 1 >= NumLevels()) {
    return SampleLevel(level0, u, v);
  }
  return (1.0f - alpha) * SampleLevel(level0, u, v) +
         alpha * SampleLevel(level0 + 1, u, v);
}

namespace {

cv::Scalar RandomColor(SyntheticRandom* rng) {
  return cv::Scalar(
      rng->Uniform(0, 255), rng->Uniform(0, 255), rng->Uniform(0, 255));
}

cv::Point RandomPoint(SyntheticRandom* rng, int width, int height) {
  return cv::Point(rng->UniformInt(0, width - 1),
                   rng->UniformInt(0, height - 1));
}

// Coloured value noise: random grids of doubling resolution with amplitude
// falling by 0.55 per octave, accumulated coarse to fine (the running sum is
// upsampled bicubically before each finer grid is added), then upsampled to
// the texture size.
cv::Mat ValueNoise(SyntheticRandom* rng,
                   int width,
                   int height,
                   int base_cells,
                   int num_octaves) {
  cv::Mat sum;
  double amplitude = 1.0;
  int cells = base_cells;
  for (int octave = 0; octave < num_octaves; ++octave) {
    const int gw = std::max(2, std::min(cells, width));
    const int gh =
        std::max(2, std::min(cells * height / std::max(1, width), height));
    cv::Mat grid(gh, gw, CV_32FC3);
    for (int y = 0; y < gh; ++y) {
      for (int x = 0; x < gw; ++x) {
        grid.at<cv::Vec3f>(y, x) =
            cv::Vec3f(static_cast<float>(rng->Uniform(-1, 1) * amplitude),
                      static_cast<float>(rng->Uniform(-1, 1) * amplitude),
                      static_cast<float>(rng->Uniform(-1, 1) * amplitude));
      }
    }
    if (sum.empty()) {
      sum = grid;
    } else {
      cv::resize(sum, sum, grid.size(), 0, 0, cv::INTER_CUBIC);
      sum += grid;
    }
    amplitude *= 0.55;
    cells *= 2;
  }
  cv::resize(sum, sum, cv::Size(width, height), 0, 0, cv::INTER_CUBIC);
  return sum;
}

void DrawRandomShapes(SyntheticRandom* rng, int num_shapes, cv::Mat* image) {
  const int w = image->cols;
  const int h = image->rows;
  const int s = std::min(w, h);
  for (int i = 0; i < num_shapes; ++i) {
    // Sizes spread log-uniformly from ~1% to ~20% of the texture side, the
    // upper end capped at 20% of 512 texels times the square root of the
    // side / 512 (so that large textures do not just pile up huge shapes).
    const double max_size = 0.2 * 512.0 * std::sqrt(std::max(1.0, s / 512.0));
    const double min_size = std::min(0.01 * s, 0.25 * max_size);
    const double size = std::exp(rng->Uniform(
        std::log(min_size), std::log(std::min(0.2 * s, max_size))));
    const int r = std::max(2, static_cast<int>(size));
    const cv::Scalar color = RandomColor(rng);
    const int thickness =
        rng->Uniform() < 0.5 ? cv::FILLED : rng->UniformInt(1, 1 + r / 8);
    const cv::Point c = RandomPoint(rng, w, h);
    switch (rng->UniformInt(0, 4)) {
      case 0:
        cv::circle(*image, c, r, color, thickness, cv::LINE_AA);
        break;
      case 1:
        cv::rectangle(
            *image,
            c,
            c + cv::Point(rng->UniformInt(-r, r), rng->UniformInt(-r, r)),
            color,
            thickness,
            cv::LINE_AA);
        break;
      case 2:
        cv::ellipse(*image,
                    c,
                    cv::Size(r, std::max(1, rng->UniformInt(r / 4, r))),
                    rng->Uniform(0, 180),
                    0,
                    360,
                    color,
                    thickness,
                    cv::LINE_AA);
        break;
      case 3: {
        std::vector<cv::Point> polygon;
        const int n = rng->UniformInt(3, 6);
        for (int k = 0; k < n; ++k) {
          polygon.push_back(
              c + cv::Point(rng->UniformInt(-r, r), rng->UniformInt(-r, r)));
        }
        if (thickness == cv::FILLED) {
          cv::fillPoly(*image,
                       std::vector<std::vector<cv::Point>>{polygon},
                       color,
                       cv::LINE_AA);
        } else {
          cv::polylines(*image, polygon, true, color, thickness, cv::LINE_AA);
        }
        break;
      }
      default:
        cv::line(*image,
                 c,
                 c + cv::Point(rng->UniformInt(-2 * r, 2 * r),
                               rng->UniformInt(-2 * r, 2 * r)),
                 color,
                 std::max(1, thickness),
                 cv::LINE_AA);
        break;
    }
  }
}

void DrawRandomText(SyntheticRandom* rng, int num_strings, cv::Mat* image) {
  static const char kChars[] = "ABCDEFGHJKLMNPQRSTUVWXYZ0123456789#&%@";
  const int fonts[] = {cv::FONT_HERSHEY_SIMPLEX,
                       cv::FONT_HERSHEY_DUPLEX,
                       cv::FONT_HERSHEY_COMPLEX,
                       cv::FONT_HERSHEY_TRIPLEX,
                       cv::FONT_HERSHEY_PLAIN};
  const int s = std::min(image->cols, image->rows);
  for (int i = 0; i < num_strings; ++i) {
    std::string text;
    const int length = rng->UniformInt(2, 7);
    for (int k = 0; k < length; ++k) {
      text.push_back(kChars[rng->UniformInt(0, sizeof(kChars) - 2)]);
    }
    const double scale =
        std::sqrt(std::max(s / 512.0, 0.25)) * rng->Uniform(0.5, 2.5);
    cv::putText(*image,
                text,
                RandomPoint(rng, image->cols, image->rows),
                fonts[rng->UniformInt(0, 4)],
                scale,
                RandomColor(rng),
                std::max(1, static_cast<int>(scale * rng->Uniform(1, 3))),
                cv::LINE_AA);
  }
}

cv::Mat NoiseToImage(const cv::Mat& noise,
                     const cv::Scalar& base,
                     double contrast) {
  cv::Mat image;
  cv::Mat result;
  noise.convertTo(result, CV_32FC3, contrast);
  result += base;
  result.convertTo(image, CV_8UC3);
  return image;
}

}  // namespace

cv::Mat GenerateRandomTexture(uint64_t seed, int width, int height) {
  SyntheticRandom rng(SyntheticRandom::Mix(seed, 0x7e47));
  const cv::Scalar base(
      rng.Uniform(60, 200), rng.Uniform(60, 200), rng.Uniform(60, 200));
  cv::Mat image =
      NoiseToImage(ValueNoise(&rng, width, height, 4, 7), base, 70.0);
  const double area_scale =
      static_cast<double>(width) * height / (512.0 * 512.0);
  DrawRandomShapes(&rng, static_cast<int>(120 * area_scale), &image);
  DrawRandomText(
      &rng, static_cast<int>(25 * std::min(area_scale, 6.0)), &image);
  // Fine speckle so that flat shapes still carry texture.
  cv::Mat fine_signed;
  ValueNoise(&rng, width, height, width / 6, 1)
      .convertTo(fine_signed, CV_32FC3, 18.0);
  cv::Mat image_f;
  image.convertTo(image_f, CV_32FC3);
  image_f += fine_signed;
  image_f.convertTo(image, CV_8UC3);
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.7);
  return image;
}

cv::Mat GenerateWindowTileTexture(uint64_t seed, int width, int height) {
  SyntheticRandom rng(SyntheticRandom::Mix(seed, 0x3177));
  const cv::Scalar wall(
      rng.Uniform(120, 200), rng.Uniform(120, 200), rng.Uniform(120, 200));
  cv::Mat image =
      NoiseToImage(ValueNoise(&rng, width, height, 8, 5), wall, 40.0);
  // Window: frame, dark glass, cross mullions, sill.
  const cv::Point p0(width / 5, height / 5);
  const cv::Point p1(width * 4 / 5, height * 7 / 10);
  const int frame = std::max(2, width / 30);
  cv::rectangle(image,
                p0 - cv::Point(frame, frame),
                p1 + cv::Point(frame, frame),
                cv::Scalar(235, 235, 235),
                cv::FILLED,
                cv::LINE_AA);
  cv::rectangle(
      image,
      p0,
      p1,
      cv::Scalar(rng.Uniform(40, 90), rng.Uniform(30, 70), rng.Uniform(20, 50)),
      cv::FILLED,
      cv::LINE_AA);
  // Reflections in the glass.
  for (int i = 0; i < 6; ++i) {
    const cv::Point a(rng.UniformInt(p0.x, p1.x), rng.UniformInt(p0.y, p1.y));
    cv::line(image,
             a,
             a + cv::Point(width / 10, -height / 10),
             cv::Scalar(120, 120, 130),
             std::max(1, width / 60),
             cv::LINE_AA);
  }
  const cv::Point mid((p0.x + p1.x) / 2, (p0.y + p1.y) / 2);
  cv::line(image,
           cv::Point(mid.x, p0.y),
           cv::Point(mid.x, p1.y),
           cv::Scalar(235, 235, 235),
           frame,
           cv::LINE_AA);
  cv::line(image,
           cv::Point(p0.x, mid.y),
           cv::Point(p1.x, mid.y),
           cv::Scalar(235, 235, 235),
           frame,
           cv::LINE_AA);
  cv::rectangle(image,
                cv::Point(p0.x - 3 * frame, p1.y + frame),
                cv::Point(p1.x + 3 * frame, p1.y + 3 * frame),
                cv::Scalar(90, 100, 110),
                cv::FILLED,
                cv::LINE_AA);
  // A few bricks so that the wall itself has corners.
  for (int y = 0; y < height; y += height / 12) {
    for (int x = ((y / (height / 12)) % 2) * width / 12; x < width;
         x += width / 6) {
      if (x > p0.x - 2 * frame && x < p1.x + 2 * frame &&
          y > p0.y - 2 * frame && y < p1.y + 4 * frame) {
        continue;
      }
      cv::rectangle(image,
                    cv::Point(x, y),
                    cv::Point(x + width / 6 - 2, y + height / 12 - 2),
                    wall * rng.Uniform(0.6, 0.95),
                    1,
                    cv::LINE_AA);
    }
  }
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.7);
  return image;
}

cv::Mat GenerateSmoothTexture(uint64_t seed, int width, int height) {
  SyntheticRandom rng(SyntheticRandom::Mix(seed, 0x5300));
  const cv::Scalar base(
      rng.Uniform(50, 110), rng.Uniform(50, 110), rng.Uniform(50, 110));
  cv::Mat image =
      NoiseToImage(ValueNoise(&rng, width, height, 4, 6), base, 25.0);
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.7);
  return image;
}

std::vector<cv::Mat> ReadTextureImages(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    ThrowError("texture_dir ", dir, " is not a directory");
  }
  std::vector<std::string> paths;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) {
      return std::tolower(c);
    });
    if (ext == ".jpg" || ext == ".jpeg" || ext == ".png" || ext == ".bmp" ||
        ext == ".tif" || ext == ".tiff") {
      paths.push_back(entry.path().string());
    }
  }
  if (ec) {
    ThrowError("cannot list texture_dir ", dir, ": ", ec.message());
  }
  std::sort(paths.begin(), paths.end());
  std::vector<cv::Mat> images;
  for (const std::string& path : paths) {
    cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
    if (image.empty()) {
      ThrowError("cannot read texture image ", path);
    }
    if (image.cols < 16 || image.rows < 16) {
      ThrowError("texture image ", path, " is smaller than 16x16");
    }
    images.push_back(image);
  }
  if (images.empty()) {
    ThrowError("texture_dir ", dir, " holds no image");
  }
  return images;
}

}  // namespace colmap_gcn
