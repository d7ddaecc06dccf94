#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace colmap_gcn {

// An RGB texture (stored BGR, 8 bit, as OpenCV) with a mipmap pyramid,
// sampled with wrap-around ("repeat") addressing and trilinear filtering.
// Texture coordinates (u, v) are in units of the whole texture: u = 1 spans
// its width once, u = 2.5 repeats it two and a half times.
class Texture {
 public:
  Texture() = default;
  explicit Texture(const cv::Mat& bgr);

  int Width() const { return levels_.empty() ? 0 : levels_[0].cols; }
  int Height() const { return levels_.empty() ? 0 : levels_[0].rows; }
  int NumLevels() const { return static_cast<int>(levels_.size()); }

  // Colour (B, G, R in [0, 255]) at (u, v); `lod` is the mipmap level
  // (log2 of texels per pixel, 0 = full resolution, fractional = trilinear).
  Eigen::Vector3f Sample(double u, double v, double lod) const;

 private:
  Eigen::Vector3f SampleLevel(int level, double u, double v) const;

  std::vector<cv::Mat> levels_;
};

// Procedural textures, deterministic for a seed. All are rich in corners and
// blobs at several scales so that SIFT finds distinctive features: coloured
// value noise with several octaves, random filled and outlined shapes and
// random text.
cv::Mat GenerateRandomTexture(uint64_t seed, int width, int height);

// One facade tile: a wall patch with a framed window, for repetitive facades
// (the same tile repeated verbatim across the facade).
cv::Mat GenerateWindowTileTexture(uint64_t seed, int width, int height);

// A dim, smooth texture with few features (plaster/stone) used for roofs.
cv::Mat GenerateSmoothTexture(uint64_t seed, int width, int height);

// Images (*.jpg, *.jpeg, *.png, *.bmp, *.tif, *.tiff) in a folder, sorted by
// file name. Throws Error if the folder cannot be read or holds no image.
std::vector<cv::Mat> ReadTextureImages(const std::string& dir);

}  // namespace colmap_gcn
