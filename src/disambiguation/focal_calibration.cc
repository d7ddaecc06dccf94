#include "disambiguation/focal_calibration.h"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

#include "util/error.h"
#include "util/option_check.h"

namespace colmap_gcn {
namespace {

PinholeIntrinsics Scaled(const PinholeIntrinsics& camera, const double scale) {
  PinholeIntrinsics scaled = camera;
  scaled.fx *= scale;
  scaled.fy *= scale;
  return scaled;
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0;
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  return values[mid];
}

// Median inconsistency of the pairs in `subset` with the cameras scaled by
// `scales`.
double MedianCost(const std::vector<PinholeIntrinsics>& cameras,
                  const std::vector<double>& scales,
                  const std::vector<FundamentalPair>& pairs,
                  const std::vector<int>& subset) {
  std::vector<double> costs;
  costs.reserve(subset.size());
  for (const int p : subset) {
    const FundamentalPair& pair = pairs[p];
    const Eigen::Matrix3d K1 =
        Scaled(cameras[pair.camera1], scales[pair.camera1]).K();
    const Eigen::Matrix3d K2 =
        Scaled(cameras[pair.camera2], scales[pair.camera2]).K();
    costs.push_back(EssentialInconsistency(K2.transpose() * pair.F * K1));
  }
  return Median(costs);
}

// The factor f minimising cost(f) over [min_scale, max_scale] relative to
// `base`: a log-spaced grid, then two finer grids around the best step.
//
// Returns `base` (*accepted false) when the coarse grid's best is within
// kEdgeSteps of either end of the range: the criterion then has no minimum
// inside it (near-planar pairs, noisy F, narrow fields of view: figurine's
// 27-degree lens drove it to 0.54 of a guess that was 0.59 of the truth;
// docs/lookalike.md) and the database's value is the better guess.
constexpr int kEdgeSteps = 8;

template <typename Cost>
double MinimiseScale(const Cost& cost,
                     const double base,
                     const FocalCalibrationOptions& options,
                     bool* accepted) {
  *accepted = false;
  double low = std::log(options.min_scale);
  double high = std::log(options.max_scale);
  double best = 0;
  for (int round = 0; round < 3; ++round) {
    const int n = options.num_grid_steps;
    const double step = (high - low) / (n - 1);
    double best_cost = 0;
    int best_index = 0;
    for (int i = 0; i < n; ++i) {
      const double x = low + i * step;
      const double c = cost(base * std::exp(x));
      // Ties by the smaller |log scale|: stay near the database's value.
      if (i == 0 || c < best_cost ||
          (c == best_cost && std::abs(x) < std::abs(best))) {
        best_cost = c;
        best = x;
        best_index = i;
      }
    }
    if (round == 0 &&
        (best_index < kEdgeSteps || best_index >= n - kEdgeSteps)) {
      return base;
    }
    low = best - step;
    high = best + step;
  }
  *accepted = true;
  return base * std::exp(best);
}

}  // namespace

void FocalCalibrationOptions::Check() const {
  CHECK_OPTION_GT(min_scale, 0.0);
  CHECK_OPTION_GT(max_scale, min_scale);
  CHECK_OPTION_GE(num_grid_steps, 2 * kEdgeSteps + 1);
  CHECK_OPTION_GE(min_images_per_camera, 1);
  CHECK_OPTION_GE(min_pairs_per_camera, 1);
  CHECK_OPTION_GE(min_num_pairs, 1);
}

double EssentialInconsistency(const Eigen::Matrix3d& E) {
  if (!E.allFinite()) return 1;
  const Eigen::Vector3d s =
      Eigen::JacobiSVD<Eigen::Matrix3d>(E).singularValues();
  if (s(0) + s(1) <= 0) return 1;
  return (s(0) - s(1)) / (s(0) + s(1));
}

FocalCalibrationResult SelfCalibrateFocalLengths(
    const std::vector<PinholeIntrinsics>& cameras,
    const std::vector<bool>& trusted,
    const std::vector<int>& num_images_per_camera,
    const std::vector<FundamentalPair>& pairs,
    const FocalCalibrationOptions& options) {
  options.Check();
  const int num_cameras = static_cast<int>(cameras.size());
  if (trusted.size() != cameras.size() ||
      num_images_per_camera.size() != cameras.size()) {
    ThrowError("focal self-calibration: ",
               cameras.size(),
               " cameras but ",
               trusted.size(),
               " trust flags and ",
               num_images_per_camera.size(),
               " image counts");
  }
  FocalCalibrationResult result;
  result.cameras = cameras;
  result.scales.assign(num_cameras, 1.0);
  result.calibrated.assign(num_cameras, false);
  // Pairs touching a guessed camera, overall and per camera.
  std::vector<int> guessed_pairs;
  std::vector<std::vector<int>> camera_pairs(num_cameras);
  for (size_t p = 0; p < pairs.size(); ++p) {
    const int c1 = pairs[p].camera1;
    const int c2 = pairs[p].camera2;
    if (c1 < 0 || c2 < 0 || c1 >= num_cameras || c2 >= num_cameras) {
      ThrowError("focal self-calibration: pair ",
                 p,
                 " names camera ",
                 std::max(c1, c2),
                 " of ",
                 num_cameras);
    }
    if (trusted[c1] && trusted[c2]) continue;
    guessed_pairs.push_back(static_cast<int>(p));
    camera_pairs[c1].push_back(static_cast<int>(p));
    if (c2 != c1) camera_pairs[c2].push_back(static_cast<int>(p));
  }
  result.num_pairs = static_cast<int>(guessed_pairs.size());
  if (result.num_pairs < options.min_num_pairs) return result;
  std::vector<double>& scales = result.scales;
  std::vector<bool>& calibrated = result.calibrated;
  result.cost_before = MedianCost(cameras, scales, pairs, guessed_pairs);

  // 1. One scale factor shared by every guessed camera.
  std::vector<bool> own(num_cameras, false);
  auto set_shared = [&](double scale) {
    for (int c = 0; c < num_cameras; ++c) {
      if (!trusted[c] && !own[c]) scales[c] = scale;
    }
  };
  auto shared_cost = [&](double scale) {
    set_shared(scale);
    return MedianCost(cameras, scales, pairs, guessed_pairs);
  };
  auto solve_shared = [&] {
    bool accepted = false;
    set_shared(MinimiseScale(shared_cost, 1.0, options, &accepted));
    for (int c = 0; c < num_cameras; ++c) {
      if (!trusted[c] && !own[c]) calibrated[c] = accepted;
    }
  };
  solve_shared();

  // 2. Cameras with enough images and pairs get their own (in camera order,
  //    two sweeps), then the shared factor of the rest is solved again.
  bool any_own = false;
  for (int c = 0; c < num_cameras; ++c) {
    own[c] = !trusted[c] &&
             num_images_per_camera[c] >= options.min_images_per_camera &&
             static_cast<int>(camera_pairs[c].size()) >=
                 options.min_pairs_per_camera;
    any_own |= own[c];
  }
  if (any_own) {
    FocalCalibrationOptions local = options;
    local.min_scale = 0.7;
    local.max_scale = 1.0 / 0.7;
    for (int sweep = 0; sweep < 2; ++sweep) {
      for (int c = 0; c < num_cameras; ++c) {
        if (!own[c]) continue;
        auto cost = [&](double scale) {
          scales[c] = scale;
          return MedianCost(cameras, scales, pairs, camera_pairs[c]);
        };
        const double base = scales[c];
        bool accepted = false;
        scales[c] = MinimiseScale(cost, base, local, &accepted);
        // Declined: the camera keeps its start, calibrated or not.
        calibrated[c] = calibrated[c] || accepted;
      }
    }
    bool any_shared = false;
    for (int c = 0; c < num_cameras; ++c) any_shared |= !trusted[c] && !own[c];
    if (any_shared) solve_shared();
  }
  for (int c = 0; c < num_cameras; ++c) {
    result.cameras[c] = Scaled(cameras[c], scales[c]);
  }
  result.cost_after = MedianCost(cameras, scales, pairs, guessed_pairs);
  return result;
}

}  // namespace colmap_gcn
