// The blocks AdaptivePairGenerator adds beyond its ranked and probe rounds:
// the per-image guarantee and the bridging between strong components
// (kEnough), the connectivity attempts (kRecall); the strong paths a
// candidate closes, which propagation classes it by; and the log-odds
// offsets over the calibrated probability (support classes, consecutive
// pairs, strong components).
#include <algorithm>

#include "controllers/adaptive_pairing.h"

namespace colmap_gcn {
namespace {

// An image joins a growing model once this many of its strong partners are
// in it (GrowthClusters).
constexpr int kMinRegistrationViews = 2;
// Clusters that grew beyond their seed pair bridge to each other.
constexpr int kMinClusterImages = 3;

}  // namespace

int AdaptivePairGenerator::CommonStrongNeighbours(int c) const {
  const std::vector<int>& a = strong_neighbours_[candidates_[c].row1];
  const std::vector<int>& b = strong_neighbours_[candidates_[c].row2];
  int common = 0;
  size_t i = 0;
  size_t j = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i] == b[j]) {
      ++common;
      ++i;
      ++j;
    } else if (a[i] < b[j]) {
      ++i;
    } else {
      ++j;
    }
  }
  return common;
}

int AdaptivePairGenerator::SupportClass(int c) const {
  const int common = CommonStrongNeighbours(c);
  if (common == 0) return 0;
  if (common == 1) return 1;
  if (common <= 3) return 2;
  if (common <= 7) return 3;
  return 4;
}

std::vector<int> AdaptivePairGenerator::GuaranteeBlock(
    const std::vector<int>& untried,
    const std::vector<uint8_t>& taken,
    size_t budget) const {
  // Partners still wanted per image: up to min_strong_partners strong ones,
  // within its patience; the taken pairs already count for both images.
  std::vector<int> wanted(image_ids_.size(), 0);
  for (size_t row = 0; row < image_ids_.size(); ++row) {
    wanted[row] =
        PartnersStillWanted(static_cast<int>(strong_neighbours_[row].size()),
                            failures_[row],
                            options_.min_strong_partners,
                            options_.image_patience);
  }
  for (size_t c = 0; c < taken.size(); ++c) {
    if (!taken[c]) continue;
    for (const int row : {candidates_[c].row1, candidates_[c].row2}) {
      wanted[row] = std::max(0, wanted[row] - 1);
    }
  }
  std::vector<int> block;
  for (const int c : untried) {  // most probable first
    if (block.size() >= budget) break;
    if (taken[c]) continue;
    const int row1 = candidates_[c].row1;
    const int row2 = candidates_[c].row2;
    if (wanted[row1] == 0 && wanted[row2] == 0) continue;
    block.push_back(c);
    wanted[row1] = std::max(0, wanted[row1] - 1);
    wanted[row2] = std::max(0, wanted[row2] - 1);
  }
  return block;
}

std::vector<int> AdaptivePairGenerator::ConnectivityBlock(
    const std::vector<int>& untried, size_t budget) const {
  // Images never attempted, then images without a strong pair, each its
  // most probable untried candidate.
  std::vector<uint8_t> attempted(image_ids_.size(), 0);
  for (const int c : yielded_) {
    attempted[candidates_[c].row1] = 1;
    attempted[candidates_[c].row2] = 1;
  }
  std::vector<int> best(image_ids_.size(), -1);
  for (const int c : untried) {
    for (const int row : {candidates_[c].row1, candidates_[c].row2}) {
      if (best[row] < 0) best[row] = c;
    }
  }
  std::vector<uint8_t> chosen(candidates_.size(), 0);
  for (size_t row = 0; row < image_ids_.size(); ++row) {
    const bool wanted =
        !attempted[row] || (strong_neighbours_[row].empty() &&
                            retries_[row] < options_.isolated_retries);
    if (!wanted || best[row] < 0 || chosen[best[row]]) continue;
    chosen[best[row]] = 1;
  }
  std::vector<int> block;
  for (const int c : untried) {
    if (chosen[c] && block.size() < budget) block.push_back(c);
  }
  return block;
}

std::vector<int> AdaptivePairGenerator::BridgeBlock(
    const std::vector<int>& untried, size_t budget) const {
  if (options_.component_patience <= 0) return {};
  // The models the mapper could grow: from the strongest pair, an image
  // joins once two of its strong partners are in (it sees points they
  // triangulated). A chain of triangles that share single images is
  // connected, but the mapper stops at it and starts a second model.
  // A lone bridge, once strong, raises the support of the candidates
  // beside it, which the next attempts then take.
  std::vector<int> strong;
  for (const int c : yielded_) {
    if (IsStrong(candidates_[c])) strong.push_back(c);
  }
  std::stable_sort(strong.begin(), strong.end(), [&](int a, int b) {
    return candidates_[a].num_inliers > candidates_[b].num_inliers;
  });
  std::vector<std::pair<int, int>> seeds;
  for (const int c : strong) {
    seeds.emplace_back(candidates_[c].row1, candidates_[c].row2);
  }
  const std::vector<int> component =
      GrowthClusters(strong_neighbours_, seeds, kMinRegistrationViews);
  std::vector<int> size(image_ids_.size(), 0);
  for (const int label : component) ++size[label];
  // A component's spent patience: its earlier bridging attempts that still
  // lead out of it, strong or not (a lone strong one joins nothing yet).
  std::vector<int> spent(image_ids_.size(), 0);
  for (const int c : yielded_) {
    const Candidate& candidate = candidates_[c];
    if (!candidate.bridge || candidate.state != Candidate::State::kObserved) {
      continue;
    }
    const int a = component[candidate.row1];
    const int b = component[candidate.row2];
    if (a == b) continue;
    ++spent[a];
    ++spent[b];
  }
  // Images outside every cluster, and a seed pair that grew no further,
  // have their own guarantee (image_patience), so no cluster's patience is
  // spent on images that match nothing.
  // One attempt per component and round, so that a bridge found raises the
  // candidates beside it before the next attempt is chosen.
  std::vector<int> wanted(image_ids_.size(), 0);
  for (size_t label = 0; label < image_ids_.size(); ++label) {
    if (size[label] >= kMinClusterImages &&
        spent[label] < options_.component_patience) {
      wanted[label] = 1;
    }
  }
  std::vector<int> block;
  for (const int c : untried) {  // most probable first
    if (block.size() >= budget) break;
    const int a = component[candidates_[c].row1];
    const int b = component[candidates_[c].row2];
    if (a == b || size[a] < kMinClusterImages || size[b] < kMinClusterImages ||
        (wanted[a] == 0 && wanted[b] == 0)) {
      continue;
    }
    block.push_back(c);
    wanted[a] = 0;
    wanted[b] = 0;
  }
  return block;
}

void AdaptivePairGenerator::FitOffsets() {
  // A matched pair's support counts the strong neighbours its images have
  // in common now; its own edge is never on those paths.
  const size_t num_classes = support_offsets_.size();
  std::vector<std::vector<double>> logits(num_classes);
  std::vector<double> num_strong(num_classes, 0);
  for (const int c : yielded_) {
    const Candidate& candidate = candidates_[c];
    if (candidate.state != Candidate::State::kObserved) continue;
    const int support = SupportClass(c);
    logits[support].push_back(Logit(calibration_.Predict(candidate.score)));
    num_strong[support] += IsStrong(candidate) ? 1 : 0;
  }
  // A class with fewer than min_propagation_samples matched pairs: none.
  const auto fitted_offset = [&](const std::vector<double>& class_logits,
                                 double class_strong) {
    return class_logits.size() >=
                   static_cast<size_t>(options_.min_propagation_samples)
               ? FitLogOddsOffset(class_logits, class_strong)
               : 0.0;
  };
  for (size_t k = 0; k < num_classes; ++k) {
    support_offsets_[k] = fitted_offset(logits[k], num_strong[k]);
  }
  // Consecutive pairs, on top of their support classes' offsets: whether
  // the name order is the capture order shows in how often they verify.
  std::vector<double> consecutive_logits;
  double consecutive_strong = 0;
  for (const int c : yielded_) {
    const Candidate& candidate = candidates_[c];
    if (candidate.state != Candidate::State::kObserved ||
        !candidate.consecutive) {
      continue;
    }
    consecutive_logits.push_back(Logit(calibration_.Predict(candidate.score)) +
                                 support_offsets_[SupportClass(c)]);
    consecutive_strong += IsStrong(candidate) ? 1 : 0;
  }
  consecutive_offset_ = fitted_offset(consecutive_logits, consecutive_strong);
  // Components are frozen after round 1 and fitted on the pairs matched
  // after it, so that no pair's own strong edge puts it inside one.
  if (first_components_.empty()) {
    first_components_ = ComponentLabels(strong_neighbours_);
  }
  std::vector<std::vector<double>> component_logits(image_ids_.size());
  std::vector<double> component_strong(image_ids_.size(), 0);
  for (size_t i = rounds_.front().num_pairs; i < yielded_.size(); ++i) {
    const int c = yielded_[i];
    const Candidate& candidate = candidates_[c];
    const int label = first_components_[candidate.row1];
    if (candidate.state != Candidate::State::kObserved ||
        label != first_components_[candidate.row2]) {
      continue;
    }
    component_logits[label].push_back(OffsetLogit(c));
    component_strong[label] += IsStrong(candidate) ? 1 : 0;
  }
  component_offsets_ = RelativeLogOddsOffsets(
      std::move(component_logits),
      component_strong,
      static_cast<size_t>(options_.min_propagation_samples));
}

double AdaptivePairGenerator::OffsetLogit(int c) const {
  const Candidate& candidate = candidates_[c];
  return Logit(calibration_.Predict(candidate.score)) +
         support_offsets_[SupportClass(c)] +
         (candidate.consecutive ? consecutive_offset_ : 0.0);
}

double AdaptivePairGenerator::Probability(int c) const {
  const Candidate& candidate = candidates_[c];
  const int label =
      first_components_.empty() ? -1 : first_components_[candidate.row1];
  return Sigmoid(OffsetLogit(c) +
                 (label >= 0 && label == first_components_[candidate.row2]
                      ? component_offsets_[label]
                      : 0.0));
}

}  // namespace colmap_gcn
