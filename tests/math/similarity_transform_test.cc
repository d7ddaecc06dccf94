#include "math/similarity_transform.h"

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

namespace colmap_gcn {
namespace {

TEST(EstimateSimilarity, RecoversKnownSimilarity) {
  Similarity3d truth;
  truth.scale = 2.5;
  truth.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())
                       .toRotationMatrix();
  truth.translation = Eigen::Vector3d(1, -2, 3);
  std::vector<Eigen::Vector3d> src, dst;
  for (int i = 0; i < 10; ++i) {
    src.emplace_back(std::sin(i), std::cos(2 * i), 0.1 * i);
    dst.push_back(truth.Transform(src.back()));
  }
  Similarity3d estimated;
  ASSERT_TRUE(EstimateSimilarity(src, dst, &estimated));
  EXPECT_NEAR(estimated.scale, 2.5, 1e-9);
  EXPECT_LT((estimated.rotation - truth.rotation).norm(), 1e-9);
  EXPECT_LT((estimated.translation - truth.translation).norm(), 1e-9);
}

TEST(EstimateSimilarity, DegenerateInputs) {
  Similarity3d sim;
  EXPECT_FALSE(
      EstimateSimilarity({{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}, &sim));
  // Collinear: rotation about the line undetermined.
  EXPECT_FALSE(EstimateSimilarity({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}},
                                  {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}},
                                  &sim));
}

}  // namespace
}  // namespace colmap_gcn
