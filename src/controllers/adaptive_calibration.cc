#include "controllers/adaptive_calibration.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "scene/database.h"

namespace colmap_gcn {
namespace {

// The bimodality an Otsu split needs to be taken as the collection's cut:
// a unimodal Gaussian's best split explains 2/pi = 0.64 of the variance,
// a uniform's 0.75; two separated modes approach 1.
constexpr double kMinBetweenClassShare = 0.75;
constexpr size_t kMinCutSamples = 20;
// The lower Otsu class is taken for accidental verifications only when its
// median is at most this many times COLMAP's default min_num_inliers.
constexpr double kMaxAccidentalMedian = 2.0;
// One pseudo-sample at 1/2 added to each calibration step, so a step of a
// few pairs claims neither certainty nor, at the low end where a failed
// exploration pair may stand alone, the collection's overall rate.
constexpr double kCalibrationPrior = 1.0;
constexpr double kCalibrationPriorRate = 0.5;
// Weight of the Gaussian prior on a support class's log-odds offset: a
// class of a few pairs that all verified strongly gets a moderate raise,
// not certainty.
constexpr double kOffsetPrior = 2.0;

}  // namespace

double Logit(double p) {
  const double q = std::clamp(p, 1e-3, 1 - 1e-3);
  return std::log(q / (1 - q));
}

double Sigmoid(double x) { return 1 / (1 + std::exp(-x)); }

// sum_i (sigmoid(logits_i + d) - y_i) + kOffsetPrior d = 0 by bisection (the
// left side increases with d).
double FitLogOddsOffset(const std::vector<double>& logits,
                        double num_positive) {
  double low = -6;
  double high = 6;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double mid = 0.5 * (low + high);
    double sum = kOffsetPrior * mid - num_positive;
    for (const double logit : logits) sum += Sigmoid(logit + mid);
    if (sum < 0) {
      low = mid;
    } else {
      high = mid;
    }
  }
  return 0.5 * (low + high);
}

std::vector<double> RelativeLogOddsOffsets(
    std::vector<std::vector<double>> logits,
    const std::vector<double>& num_positive,
    size_t min_samples) {
  std::vector<double> offsets(logits.size(), 0.0);
  std::vector<double> all;
  double all_positive = 0;
  for (size_t g = 0; g < logits.size(); ++g) {
    all.insert(all.end(), logits[g].begin(), logits[g].end());
    all_positive += num_positive[g];
  }
  if (all.size() < min_samples) return offsets;
  const double shared = FitLogOddsOffset(all, all_positive);
  for (size_t g = 0; g < logits.size(); ++g) {
    if (logits[g].size() < min_samples) continue;
    for (double& logit : logits[g]) logit += shared;
    offsets[g] = FitLogOddsOffset(logits[g], num_positive[g]);
  }
  return offsets;
}

void IsotonicCalibration::Fit(std::vector<std::pair<float, int>> samples) {
  lower_.clear();
  upper_.clear();
  levels_.clear();
  num_samples_ = samples.size();
  if (samples.empty()) return;
  std::sort(samples.begin(), samples.end());
  struct Block {
    float lower;
    float upper;
    double sum;
    double weight;
  };
  std::vector<Block> blocks;
  for (size_t i = 0; i < samples.size();) {
    Block block{samples[i].first, samples[i].first, 0, 0};
    size_t j = i;
    for (; j < samples.size() && samples[j].first == samples[i].first; ++j) {
      block.sum += samples[j].second;
      block.weight += 1;
    }
    i = j;
    blocks.push_back(block);
    // Pool adjacent violators: merge while the previous step is higher.
    while (blocks.size() >= 2) {
      Block& prev = blocks[blocks.size() - 2];
      const Block& last = blocks.back();
      if (prev.sum * last.weight <= last.sum * prev.weight) break;
      prev.sum += last.sum;
      prev.weight += last.weight;
      prev.upper = last.upper;
      blocks.pop_back();
    }
  }
  double level = 0;
  for (const Block& block : blocks) {
    const double shrunk =
        (block.sum + kCalibrationPrior * kCalibrationPriorRate) /
        (block.weight + kCalibrationPrior);
    level = std::max(level, shrunk);  // shrinking may break monotonicity
    lower_.push_back(block.lower);
    upper_.push_back(block.upper);
    levels_.push_back(level);
  }
}

double IsotonicCalibration::Predict(float score) const {
  if (levels_.empty()) return 0;
  // The step whose range holds the score, or linear between the two steps
  // around a gap; beyond the samples, the end steps.
  const auto it = std::upper_bound(lower_.begin(), lower_.end(), score);
  if (it == lower_.begin()) return levels_.front();
  const size_t i = static_cast<size_t>(it - lower_.begin()) - 1;
  if (score <= upper_[i] || i + 1 == levels_.size()) return levels_[i];
  const double t = (static_cast<double>(score) - upper_[i]) /
                   (static_cast<double>(lower_[i + 1]) - upper_[i]);
  return levels_[i] + t * (levels_[i + 1] - levels_[i]);
}

int LearnStrongInlierCut(const std::vector<size_t>& verified_inliers,
                         int min_cut,
                         int max_cut) {
  if (verified_inliers.size() < kMinCutSamples) {
    return min_cut;
  }
  std::vector<double> values;
  values.reserve(verified_inliers.size());
  for (const size_t inliers : verified_inliers) {
    values.push_back(
        std::log(static_cast<double>(std::max<size_t>(1, inliers))));
  }
  std::sort(values.begin(), values.end());
  const double n = static_cast<double>(values.size());
  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / n;
  double variance = 0;
  for (const double v : values) variance += (v - mean) * (v - mean);
  variance /= n;
  if (variance <= 0) return min_cut;
  double best = -1;
  double best_cut = 0;
  double prefix = 0;
  for (size_t k = 1; k < values.size(); ++k) {
    prefix += values[k - 1];
    if (values[k - 1] == values[k]) continue;
    const double w0 = static_cast<double>(k) / n;
    const double m0 = prefix / static_cast<double>(k);
    const double m1 = (mean * n - prefix) / (n - static_cast<double>(k));
    const double between = w0 * (1 - w0) * (m0 - m1) * (m0 - m1);
    if (between > best) {
      best = between;
      best_cut = 0.5 * (values[k - 1] + values[k]);
    }
  }
  if (best / variance < kMinBetweenClassShare) {
    return min_cut;
  }
  // The accidental mode sits just above COLMAP's verification threshold
  // (15-35 inliers on a repetitive courtyard); a lower class whose median
  // is far above it is a weaker mode of real pairs, not accidents.
  const size_t num_lower = static_cast<size_t>(std::count_if(
      values.begin(), values.end(), [&](double v) { return v < best_cut; }));
  if (std::exp(values[num_lower / 2]) >
      kMaxAccidentalMedian * kDefaultMinNumInliers) {
    return min_cut;
  }
  const int cut = static_cast<int>(std::ceil(std::exp(best_cut)));
  return std::clamp(cut, min_cut, max_cut);
}

bool IsRelativelyStrong(size_t inliers,
                        size_t best_inliers1,
                        size_t best_inliers2,
                        double ratio) {
  const size_t reference = std::min(best_inliers1, best_inliers2);
  return static_cast<double>(inliers) >= ratio * static_cast<double>(reference);
}

int PartnersStillWanted(int strong_partners,
                        int failures,
                        int min_partners,
                        int patience) {
  const int lacking = min_partners - strong_partners;
  const int left = patience - failures;
  return std::max(0, std::min(lacking, left));
}

std::vector<int> ComponentLabels(
    const std::vector<std::vector<int>>& neighbours) {
  std::vector<int> parent(neighbours.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[v] != v) {
      parent[v] = parent[parent[v]];
      v = parent[v];
    }
    return v;
  };
  for (size_t v = 0; v < neighbours.size(); ++v) {
    for (const int w : neighbours[v]) {
      const int a = find(static_cast<int>(v));
      const int b = find(w);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  for (size_t v = 0; v < parent.size(); ++v) {
    parent[v] = find(static_cast<int>(v));
  }
  return parent;
}

std::vector<int> GrowthClusters(const std::vector<std::vector<int>>& neighbours,
                                const std::vector<std::pair<int, int>>& seeds,
                                int min_views) {
  const int num_vertices = static_cast<int>(neighbours.size());
  min_views = std::max(1, min_views);
  std::vector<int> label(neighbours.size(), -1);
  std::vector<int> views(neighbours.size(), 0);  // in the growing cluster
  std::vector<int> touched;
  std::vector<int> queue;
  for (const auto& [a, b] : seeds) {
    if (a < 0 || b < 0 || a >= num_vertices || b >= num_vertices || a == b ||
        label[a] >= 0 || label[b] >= 0) {
      continue;
    }
    queue = {a, b};
    label[a] = label[b] = a;
    for (size_t next = 0; next < queue.size(); ++next) {
      for (const int w : neighbours[queue[next]]) {
        if (label[w] >= 0) continue;
        if (views[w]++ == 0) touched.push_back(w);
        if (views[w] == min_views) {
          label[w] = a;
          queue.push_back(w);
        }
      }
    }
    for (const int w : touched) views[w] = 0;
    touched.clear();
  }
  for (int v = 0; v < num_vertices; ++v) {
    if (label[v] < 0) label[v] = v;
  }
  return label;
}

size_t CountComponents(const std::vector<std::vector<int>>& neighbours) {
  const std::vector<int> labels = ComponentLabels(neighbours);
  size_t components = 0;
  for (size_t v = 0; v < labels.size(); ++v) {
    components += labels[v] == static_cast<int>(v) ? 1 : 0;
  }
  return components;
}

}  // namespace colmap_gcn
