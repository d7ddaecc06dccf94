#include "controllers/adaptive_pairing.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "retrieval/global_descriptors.h"
#include "retrieval/knn.h"
#include "util/error.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/pair_key.h"
#include "util/random.h"

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
// Classes of common strong neighbours: 0, 1, 2-3, 4-7, >= 8.
constexpr int kSupportClasses = 5;

double Logit(double p) {
  const double q = std::clamp(p, 1e-3, 1 - 1e-3);
  return std::log(q / (1 - q));
}

double Sigmoid(double x) { return 1 / (1 + std::exp(-x)); }

// Weight of the Gaussian prior on a support class's log-odds offset: a
// class of a few pairs that all verified strongly gets a moderate raise,
// not certainty.
constexpr double kOffsetPrior = 2.0;

// The log-odds offset d in [-6, 6] that maximises the class's likelihood
// under the prior: sum_i (sigmoid(logits_i + d) - y_i) + kOffsetPrior d = 0
// (bisection; the left side increases with d).
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

}  // namespace

void AdaptivePairingOptions::Check() const {
  CHECK_OPTION_GE(initial_per_image, 1);
  CHECK_OPTION_RANGE(exploration_fraction, 0.0, 1.0);
  CHECK_OPTION_GE(seed, 0);
  CHECK_OPTION(round_size,
               round_size == -1 || round_size >= 1,
               "be -1 (the number of images, at least 50) or >= 1");
  CHECK_OPTION_RANGE(min_pair_yield, 0.0, 1.0);
  CHECK_OPTION_GE(max_num_pairs, 0);
  CHECK_OPTION_GE(min_strong_inliers, 1);
  CHECK_OPTION_GE(max_strong_inliers, min_strong_inliers);
  CHECK_OPTION_GE(min_propagation_samples, 1);
  CHECK_OPTION_GE(isolated_retries, 0);
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
                         const AdaptivePairingOptions& options) {
  if (verified_inliers.size() < kMinCutSamples) {
    return options.min_strong_inliers;
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
  if (variance <= 0) return options.min_strong_inliers;
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
    return options.min_strong_inliers;
  }
  // The accidental mode sits just above COLMAP's verification threshold
  // (15-35 inliers on a repetitive courtyard); a lower class whose median
  // is far above it is a weaker mode of real pairs, not accidents.
  const size_t num_lower = static_cast<size_t>(std::count_if(
      values.begin(), values.end(), [&](double v) { return v < best_cut; }));
  if (std::exp(values[num_lower / 2]) >
      kMaxAccidentalMedian * kDefaultMinNumInliers) {
    return options.min_strong_inliers;
  }
  const int cut = static_cast<int>(std::ceil(std::exp(best_cut)));
  return std::clamp(
      cut, options.min_strong_inliers, options.max_strong_inliers);
}

AdaptivePairGenerator::AdaptivePairGenerator(
    const AdaptivePairingOptions& options,
    const std::vector<image_t>& image_ids,
    const std::vector<PairCandidate>& candidates,
    const std::string& label)
    : options_(options), label_(label), image_ids_(image_ids) {
  options_.Check();
  for (size_t i = 0; i < image_ids_.size(); ++i) {
    if (!rows_.emplace(image_ids_[i], static_cast<int>(i)).second) {
      ThrowError(label_, " pairing got duplicate image id ", image_ids_[i]);
    }
  }
  // Unordered, deduplicated (higher score kept), in row-key order.
  std::vector<std::pair<uint64_t, float>> keyed;
  keyed.reserve(candidates.size());
  for (const PairCandidate& candidate : candidates) {
    const auto it1 = rows_.find(candidate.image_id1);
    const auto it2 = rows_.find(candidate.image_id2);
    if (it1 == rows_.end() || it2 == rows_.end()) {
      ThrowError(label_,
                 " pairing got a candidate with an unknown image id (",
                 candidate.image_id1,
                 ", ",
                 candidate.image_id2,
                 ")");
    }
    if (it1->second == it2->second) continue;
    keyed.emplace_back(PairKey(it1->second, it2->second), candidate.score);
  }
  std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : a.second > b.second;
  });
  for (size_t i = 0; i < keyed.size(); ++i) {
    if (i > 0 && keyed[i].first == keyed[i - 1].first) continue;
    Candidate candidate;
    candidate.row1 = static_cast<int>(keyed[i].first >> 32);
    candidate.row2 = static_cast<int>(keyed[i].first & 0xffffffffu);
    candidate.score = keyed[i].second;
    candidate_index_.emplace(keyed[i].first,
                             static_cast<int>(candidates_.size()));
    candidates_.push_back(candidate);
  }
  incident_.assign(image_ids_.size(), {});
  for (size_t c = 0; c < candidates_.size(); ++c) {
    incident_[candidates_[c].row1].push_back(static_cast<int>(c));
    incident_[candidates_[c].row2].push_back(static_cast<int>(c));
  }
  for (size_t row = 0; row < incident_.size(); ++row) {
    std::vector<int>& list = incident_[row];
    std::stable_sort(list.begin(), list.end(), [&](int a, int b) {
      return candidates_[a].score > candidates_[b].score;
    });
  }
  Reset();
}

void AdaptivePairGenerator::Reset() {
  for (Candidate& candidate : candidates_) {
    candidate.state = Candidate::State::kUntried;
    candidate.verified = false;
    candidate.num_inliers = 0;
  }
  yielded_.clear();
  rounds_.clear();
  strong_neighbours_.assign(image_ids_.size(), {});
  strong_cut_ = options_.min_strong_inliers;
  calibration_ = IsotonicCalibration();
  support_offsets_.assign(kSupportClasses, 0.0);
  retries_.assign(image_ids_.size(), 0);
  prepared_ = false;
  next_.clear();
  next_yield_ = -1;
}

bool AdaptivePairGenerator::HasFinished() const {
  PrepareNext();
  return next_.empty();
}

std::vector<ImagePair> AdaptivePairGenerator::Next() {
  PrepareNext();
  prepared_ = false;
  std::vector<ImagePair> block;
  if (next_.empty()) return block;
  const bool connectivity = next_connectivity_;
  for (const int c : next_) {
    Candidate& candidate = candidates_[c];
    candidate.state = Candidate::State::kPending;
    yielded_.push_back(c);
    block.emplace_back(image_ids_[candidate.row1], image_ids_[candidate.row2]);
    if (connectivity) {
      for (const int row : {candidate.row1, candidate.row2}) {
        if (strong_neighbours_[row].empty()) ++retries_[row];
      }
    }
  }
  AdaptiveRound round;
  round.round = static_cast<int>(rounds_.size()) + 1;
  round.num_pairs = block.size();
  round.expected_yield = next_yield_;
  round.probe = next_probe_;
  round.connectivity = next_connectivity_;
  rounds_.push_back(round);
  round_timer_.Restart();
  next_.clear();
  return block;
}

std::vector<float> AdaptivePairGenerator::Scores() const {
  std::vector<float> scores;
  scores.reserve(yielded_.size());
  for (const int c : yielded_) scores.push_back(candidates_[c].score);
  return scores;
}

bool AdaptivePairGenerator::IsStrong(const Candidate& candidate) const {
  return candidate.state == Candidate::State::kObserved && candidate.verified &&
         candidate.num_inliers >= static_cast<size_t>(strong_cut_);
}

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

void AdaptivePairGenerator::Observe(
    const std::vector<PairVerification>& verifications) {
  prepared_ = false;
  for (const PairVerification& verification : verifications) {
    const auto it1 = rows_.find(verification.image_id1);
    const auto it2 = rows_.find(verification.image_id2);
    if (it1 == rows_.end() || it2 == rows_.end()) continue;
    const auto it = candidate_index_.find(PairKey(it1->second, it2->second));
    if (it == candidate_index_.end()) continue;
    Candidate& candidate = candidates_[it->second];
    if (candidate.state != Candidate::State::kPending) continue;
    candidate.state = Candidate::State::kObserved;
    candidate.verified = IsVerifiedTwoViewGeometry(verification.config,
                                                   verification.num_inliers);
    candidate.num_inliers = verification.num_inliers;
  }
  Refit();

  if (rounds_.empty()) return;
  AdaptiveRound& round = rounds_.back();
  round.strong_cut = strong_cut_;
  round.seconds = round_timer_.ElapsedSeconds();
  const size_t begin = yielded_.size() - round.num_pairs;
  round.num_verified = 0;
  round.num_strong = 0;
  for (size_t i = begin; i < yielded_.size(); ++i) {
    const Candidate& candidate = candidates_[yielded_[i]];
    if (candidate.state != Candidate::State::kObserved) continue;
    round.num_verified += candidate.verified ? 1 : 0;
    round.num_strong += IsStrong(candidate) ? 1 : 0;
  }
  round.total_attempted = yielded_.size();
  round.total_strong = 0;
  for (const int c : yielded_) round.total_strong += IsStrong(candidates_[c]);
  char yield[32];
  if (round.expected_yield < 0) {
    std::snprintf(yield, sizeof(yield), "n/a");
  } else {
    std::snprintf(yield, sizeof(yield), "%.2f", round.expected_yield);
  }
  char seconds[32];
  std::snprintf(seconds, sizeof(seconds), "%.1f", round.seconds);
  std::string offsets;
  for (const double offset : support_offsets_) {
    char text[16];
    std::snprintf(text, sizeof(text), "%+.1f", offset);
    offsets += (offsets.empty() ? "" : "/") + std::string(text);
  }
  LOG(INFO) << label_ << " round " << round.round
            << (round.probe          ? " (probe)"
                : round.connectivity ? " (connectivity)"
                                     : "")
            << ": " << round.num_pairs << " pairs attempted (calibrated yield "
            << yield << "), " << round.num_verified << " verified, "
            << round.num_strong << " strong (cut " << round.strong_cut
            << " inliers); " << round.total_attempted << " attempted, "
            << round.total_strong << " strong in all; support offsets "
            << offsets << "; " << seconds << " s";
}

void AdaptivePairGenerator::Refit() {
  std::vector<size_t> verified_inliers;
  for (const int c : yielded_) {
    const Candidate& candidate = candidates_[c];
    if (candidate.state == Candidate::State::kObserved && candidate.verified) {
      verified_inliers.push_back(candidate.num_inliers);
    }
  }
  strong_cut_ = LearnStrongInlierCut(verified_inliers, options_);
  for (std::vector<int>& list : strong_neighbours_) list.clear();
  for (const int c : yielded_) {
    const Candidate& candidate = candidates_[c];
    if (!IsStrong(candidate)) continue;
    strong_neighbours_[candidate.row1].push_back(candidate.row2);
    strong_neighbours_[candidate.row2].push_back(candidate.row1);
  }
  for (std::vector<int>& list : strong_neighbours_) {
    std::sort(list.begin(), list.end());
  }
  std::vector<std::pair<float, int>> samples;
  for (const int c : yielded_) {
    const Candidate& candidate = candidates_[c];
    if (candidate.state != Candidate::State::kObserved) continue;
    samples.emplace_back(candidate.score, IsStrong(candidate) ? 1 : 0);
  }
  calibration_.Fit(samples);
  // A matched pair's support counts the strong neighbours its images have
  // in common now; its own edge is never on those paths.
  std::vector<std::vector<double>> logits(kSupportClasses);
  std::vector<double> num_strong(kSupportClasses, 0);
  for (const int c : yielded_) {
    const Candidate& candidate = candidates_[c];
    if (candidate.state != Candidate::State::kObserved) continue;
    const int support = SupportClass(c);
    logits[support].push_back(Logit(calibration_.Predict(candidate.score)));
    num_strong[support] += IsStrong(candidate) ? 1 : 0;
  }
  for (int k = 0; k < kSupportClasses; ++k) {
    support_offsets_[k] =
        logits[k].size() >=
                static_cast<size_t>(options_.min_propagation_samples)
            ? FitLogOddsOffset(logits[k], num_strong[k])
            : 0;
  }
}

double AdaptivePairGenerator::Probability(int c) const {
  return Sigmoid(Logit(calibration_.Predict(candidates_[c].score)) +
                 support_offsets_[SupportClass(c)]);
}

void AdaptivePairGenerator::PrepareNext() const {
  if (prepared_) return;
  next_ = yielded_.empty() ? FirstRound() : LaterRound();
  prepared_ = true;
}

std::vector<int> AdaptivePairGenerator::FirstRound() const {
  next_yield_ = -1;
  std::vector<int> block;
  std::vector<uint8_t> chosen(candidates_.size(), 0);
  // Rank by rank over the images, so a budget keeps every image's best.
  for (int r = 0; r < options_.initial_per_image; ++r) {
    for (const std::vector<int>& list : incident_) {
      if (static_cast<int>(list.size()) <= r) continue;
      const int c = list[r];
      if (chosen[c]) continue;
      chosen[c] = 1;
      block.push_back(c);
    }
  }
  std::vector<int> rest;
  for (size_t c = 0; c < candidates_.size(); ++c) {
    if (!chosen[c]) rest.push_back(static_cast<int>(c));
  }
  std::stable_sort(rest.begin(), rest.end(), [&](int a, int b) {
    return candidates_[a].score > candidates_[b].score;
  });
  const size_t num_explore = std::min(
      rest.size(),
      static_cast<size_t>(std::ceil(options_.exploration_fraction *
                                    static_cast<double>(block.size()))));
  uint64_t state = static_cast<uint64_t>(options_.seed);
  for (size_t s = 0; s < num_explore; ++s) {
    const size_t begin = s * rest.size() / num_explore;
    const size_t end = (s + 1) * rest.size() / num_explore;
    block.push_back(rest[begin + SplitMix64(&state) % (end - begin)]);
  }
  if (options_.max_num_pairs > 0 &&
      block.size() > static_cast<size_t>(options_.max_num_pairs)) {
    block.resize(options_.max_num_pairs);
  }
  return block;
}

std::vector<int> AdaptivePairGenerator::LaterRound() const {
  next_yield_ = -1;
  next_probe_ = false;
  next_connectivity_ = false;
  size_t budget = candidates_.size();
  if (options_.max_num_pairs > 0) {
    const size_t max = static_cast<size_t>(options_.max_num_pairs);
    budget = yielded_.size() >= max ? 0 : max - yielded_.size();
  }
  bool any_observed = false;
  for (const int c : yielded_) {
    any_observed |= candidates_[c].state == Candidate::State::kObserved;
  }
  // Without results (AllPairs() without Observe()) nothing is calibrated.
  if (budget == 0 || !any_observed) return {};

  std::vector<double> probability(candidates_.size(), -1);
  std::vector<int> untried;
  for (size_t c = 0; c < candidates_.size(); ++c) {
    if (candidates_[c].state != Candidate::State::kUntried) continue;
    const int ci = static_cast<int>(c);
    probability[c] = Probability(ci);
    untried.push_back(ci);
  }
  std::stable_sort(untried.begin(), untried.end(), [&](int a, int b) {
    if (probability[a] != probability[b]) {
      return probability[a] > probability[b];
    }
    return candidates_[a].score > candidates_[b].score;
  });
  const size_t round_size = options_.round_size > 0
                                ? static_cast<size_t>(options_.round_size)
                                : std::max<size_t>(50, image_ids_.size());
  std::vector<int> block;
  double sum = 0;
  for (const int c : untried) {
    if (block.size() >= std::min(round_size, budget) ||
        probability[c] < options_.min_pair_yield) {
      break;
    }
    block.push_back(c);
    sum += probability[c];
  }
  const AdaptiveRound& last = rounds_.back();
  const double last_yield = last.num_pairs == 0
                                ? 0.0
                                : static_cast<double>(last.num_strong) /
                                      static_cast<double>(last.num_pairs);
  if (block.empty() && last_yield >= options_.min_pair_yield) {
    // Probe: the last round verified well, so the candidates just below
    // it are tried rather than trusted to the extrapolated calibration.
    const size_t probe_size = std::min(
        {round_size, budget, std::max<size_t>(10, image_ids_.size() / 2)});
    for (const int c : untried) {
      if (block.size() >= probe_size) break;
      block.push_back(c);
      sum += probability[c];
    }
    next_probe_ = !block.empty();
  }
  if (block.empty()) {
    // Connectivity: images never attempted, then images without a strong
    // pair, each its most probable untried candidate.
    next_connectivity_ = true;
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
    for (const int c : untried) {
      if (chosen[c] && block.size() < budget) {
        block.push_back(c);
        sum += probability[c];
      }
    }
  }
  if (!block.empty()) {
    next_yield_ = sum / static_cast<double>(block.size());
  } else {
    next_connectivity_ = false;
    LOG(INFO) << label_ << ": finished after " << rounds_.size()
              << " rounds; no candidate left with a calibrated probability "
                 "of a strong verification >= "
              << options_.min_pair_yield
              << (budget == 0 ? " within max_num_pairs" : "");
  }
  return block;
}

AdaptiveGcnPairingOptions::AdaptiveGcnPairingOptions() {
  gcn.k1 = 100;
  knn.k = 100;
}

void AdaptiveGcnPairingOptions::Check() const {
  gcn.Check();
  adaptive.Check();
  CHECK_OPTION_RANGE(similarity_weight, 0.0, 1.0);
  if (similarity_weight > 0) knn.Check();
}

namespace {

// Each unordered pair's percentile in (0, 1] within its list (the higher
// score of a duplicate kept; ties share their mean percentile), by pair id.
std::unordered_map<image_pair_t, double> ScorePercentiles(
    const std::vector<PairCandidate>& candidates) {
  std::unordered_map<image_pair_t, float> best;
  for (const PairCandidate& candidate : candidates) {
    if (candidate.image_id1 == candidate.image_id2) continue;
    const auto [it, inserted] = best.emplace(
        ImagePairToPairId(candidate.image_id1, candidate.image_id2),
        candidate.score);
    if (!inserted) it->second = std::max(it->second, candidate.score);
  }
  std::vector<float> scores;
  scores.reserve(best.size());
  for (const auto& [pair_id, score] : best) scores.push_back(score);
  std::sort(scores.begin(), scores.end());
  std::unordered_map<image_pair_t, double> percentiles;
  const double n = static_cast<double>(scores.size());
  for (const auto& [pair_id, score] : best) {
    const double low = static_cast<double>(
        std::lower_bound(scores.begin(), scores.end(), score) - scores.begin());
    const double high = static_cast<double>(
        std::upper_bound(scores.begin(), scores.end(), score) - scores.begin());
    percentiles.emplace(pair_id, (low + high + 1) / (2 * n));
  }
  return percentiles;
}

}  // namespace

std::vector<PairCandidate> CombinePriors(const std::vector<PairCandidate>& a,
                                         const std::vector<PairCandidate>& b,
                                         double weight_b) {
  const std::unordered_map<image_pair_t, double> pa = ScorePercentiles(a);
  const std::unordered_map<image_pair_t, double> pb = ScorePercentiles(b);
  std::vector<image_pair_t> pair_ids;
  for (const auto& [pair_id, p] : pa) pair_ids.push_back(pair_id);
  for (const auto& [pair_id, p] : pb) {
    if (pa.count(pair_id) == 0) pair_ids.push_back(pair_id);
  }
  // Pair ids order pairs by (smaller id, larger id).
  std::sort(pair_ids.begin(), pair_ids.end());
  std::vector<PairCandidate> combined;
  combined.reserve(pair_ids.size());
  for (const image_pair_t pair_id : pair_ids) {
    const auto ia = pa.find(pair_id);
    const auto ib = pb.find(pair_id);
    const double score = (1 - weight_b) * (ia != pa.end() ? ia->second : 0.0) +
                         weight_b * (ib != pb.end() ? ib->second : 0.0);
    const ImagePair pair = PairIdToImagePair(pair_id);
    combined.push_back({pair.first, pair.second, static_cast<float>(score)});
  }
  return combined;
}

std::vector<PairCandidate> GcnModelCandidates(
    const GcnModelPairingOptions& options,
    const Database& database,
    std::vector<image_t>* image_ids) {
  std::vector<PairCandidate> candidates;
  for (const ScoredImagePair& pair :
       ScoreEveryGcnCandidate(options, database)) {
    candidates.push_back({pair.image_id1, pair.image_id2, pair.score});
  }
  image_ids->clear();
  for (const DatabaseImage& image : database.ReadAllImages()) {
    image_ids->push_back(image.image_id);
  }
  return candidates;
}

namespace {

void AddAdaptiveOptions(OptionManager* manager,
                        AdaptivePairingOptions* options) {
  manager->AddDefaultOption("GcnMatching.initial_per_image",
                            &options->initial_per_image,
                            "adaptive/graphmatch: round 1's best candidates "
                            "per image");
  manager->AddDefaultOption(
      "GcnMatching.exploration_fraction",
      &options->exploration_fraction,
      "adaptive/graphmatch: round 1's share of lower-ranked candidates");
  manager->AddDefaultOption("GcnMatching.seed",
                            &options->seed,
                            "adaptive/graphmatch: seed of the exploration");
  manager->AddDefaultOption(
      "GcnMatching.round_size",
      &options->round_size,
      "adaptive/graphmatch: pairs per later round; -1: images (>= 50)");
  manager->AddDefaultOption(
      "GcnMatching.min_pair_yield",
      &options->min_pair_yield,
      "adaptive/graphmatch: stop when no candidate's calibrated P(strong "
      "verification) reaches this");
  manager->AddDefaultOption(
      "GcnMatching.max_num_pairs",
      &options->max_num_pairs,
      "adaptive/graphmatch: hard budget of attempted pairs; 0: none");
  manager->AddDefaultOption(
      "GcnMatching.min_strong_inliers",
      &options->min_strong_inliers,
      "adaptive/graphmatch: lowest learned strong-verification cut");
  manager->AddDefaultOption(
      "GcnMatching.max_strong_inliers",
      &options->max_strong_inliers,
      "adaptive/graphmatch: highest learned strong-verification cut");
  manager->AddDefaultOption(
      "GcnMatching.min_propagation_samples",
      &options->min_propagation_samples,
      "adaptive/graphmatch: matched path-closing pairs before propagation "
      "is calibrated on its own");
  manager->AddDefaultOption(
      "GcnMatching.isolated_retries",
      &options->isolated_retries,
      "adaptive/graphmatch: extra attempts for images without a strong "
      "pair");
}

}  // namespace

PairGeneratorSpec<AdaptiveGcnPairingOptions> AdaptivePairGeneratorSpec() {
  PairGeneratorSpec<AdaptiveGcnPairingOptions> spec;
  spec.name = "adaptive";
  spec.add_options = [](OptionManager* manager,
                        AdaptiveGcnPairingOptions* options) {
    GcnModelPairGeneratorSpec().add_options(manager, &options->gcn);
    KnnPairGeneratorSpec().add_options(manager, &options->knn);
    AddAdaptiveOptions(manager, &options->adaptive);
    manager->AddDefaultOption(
        "GcnMatching.similarity_weight",
        &options->similarity_weight,
        "adaptive: weight of embedding similarity in the prior (percentiles "
        "of the GCN score and of the similarity); 0: the GCN score alone");
  };
  spec.create = [](const AdaptiveGcnPairingOptions& options,
                   const PairGeneratorContext& context)
      -> std::unique_ptr<PairGenerator> {
    std::vector<image_t> image_ids;
    std::vector<PairCandidate> candidates =
        GcnModelCandidates(options.gcn, context.database, &image_ids);
    if (options.similarity_weight > 0) {
      std::vector<image_t> knn_image_ids;
      candidates = CombinePriors(
          candidates,
          SimilarityCandidates(options.knn, context.database, &knn_image_ids),
          options.similarity_weight);
    }
    return std::make_unique<AdaptivePairGenerator>(
        options.adaptive, image_ids, candidates, "adaptive");
  };
  return spec;
}

GraphMatchPairingOptions::GraphMatchPairingOptions() { knn.k = 100; }

void GraphMatchPairingOptions::Check() const {
  knn.Check();
  adaptive.Check();
}

std::vector<PairCandidate> SimilarityCandidates(
    const KnnPairingOptions& options,
    const Database& database,
    std::vector<image_t>* image_ids) {
  options.Check();
  GlobalDescriptorOptions descriptor_options = options.Descriptors();
  descriptor_options.num_threads = options.num_threads;
  descriptor_options.vlad.num_threads = options.num_threads;
  const EmbeddingMatrix embeddings =
      ComputeGlobalDescriptors(database, descriptor_options, image_ids);
  KnnOptions knn_options;
  knn_options.k = std::min<int>(
      options.k, std::max<int>(1, static_cast<int>(image_ids->size()) - 1));
  knn_options.num_threads = options.num_threads;
  knn_options.method = options.knn_method;
  std::vector<PairCandidate> candidates;
  if (image_ids->size() < 2) return candidates;
  const KnnGraph graph = ComputeKnn(embeddings, knn_options);
  for (int i = 0; i < graph.NumImages(); ++i) {
    for (int n = 0; n < graph.K(); ++n) {
      const int j = graph.indices(i, n);
      if (j < 0 || j == i) continue;
      candidates.push_back(
          {(*image_ids)[i], (*image_ids)[j], graph.similarities(i, n)});
    }
  }
  return candidates;
}

PairGeneratorSpec<GraphMatchPairingOptions> GraphMatchPairGeneratorSpec() {
  PairGeneratorSpec<GraphMatchPairingOptions> spec;
  spec.name = "graphmatch";
  spec.add_options = [](OptionManager* manager,
                        GraphMatchPairingOptions* options) {
    KnnPairGeneratorSpec().add_options(manager, &options->knn);
    AddAdaptiveOptions(manager, &options->adaptive);
  };
  spec.create = [](const GraphMatchPairingOptions& options,
                   const PairGeneratorContext& context)
      -> std::unique_ptr<PairGenerator> {
    std::vector<image_t> image_ids;
    const std::vector<PairCandidate> candidates =
        SimilarityCandidates(options.knn, context.database, &image_ids);
    return std::make_unique<AdaptivePairGenerator>(
        options.adaptive, image_ids, candidates, "graphmatch");
  };
  return spec;
}

}  // namespace colmap_gcn
