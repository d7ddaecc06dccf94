#include "controllers/adaptive_pairing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_set>

#include "util/error.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/pair_key.h"
#include "util/random.h"

namespace colmap_gcn {
namespace {

// Classes of common strong neighbours: 0, 1, 2-3, 4-7, >= 8.
constexpr int kSupportClasses = 5;

}  // namespace

void AdaptivePairingOptions::Check() const {
  CHECK_OPTION_GE(initial_per_image, 1);
  CHECK_OPTION_RANGE(exploration_fraction, 0.0, 1.0);
  CHECK_OPTION_GE(max_exploration_pairs, 0);
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
  CHECK_OPTION_RANGE(relative_strength, 0.0, 1.0);
  CHECK_OPTION_GE(min_strong_partners, 0);
  CHECK_OPTION_GE(image_patience, 0);
  CHECK_OPTION(
      max_strong_partners,
      max_strong_partners == 0 || max_strong_partners >= min_strong_partners,
      "be 0 (no cap) or >= min_strong_partners");
  CHECK_OPTION_GE(component_patience, 0);
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
  std::unordered_set<uint64_t> consecutive;
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
    if (candidate.consecutive) consecutive.insert(keyed.back().first);
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
    candidate.consecutive = consecutive.count(keyed[i].first) > 0;
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
    candidate.bridge = false;
  }
  yielded_.clear();
  rounds_.clear();
  strong_neighbours_.assign(image_ids_.size(), {});
  strong_cut_ = options_.min_strong_inliers;
  calibration_ = IsotonicCalibration();
  support_offsets_.assign(kSupportClasses, 0.0);
  consecutive_offset_ = 0;
  first_components_.clear();
  component_offsets_.assign(image_ids_.size(), 0.0);
  retries_.assign(image_ids_.size(), 0);
  failures_.assign(image_ids_.size(), 0);
  best_inliers_.assign(image_ids_.size(), 0);
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
  if (next_.empty()) {
    if (progress_) progress_->Finish();
    return block;
  }
  if (!progress_) {
    // kEnough counts toward a known total (every image with its strong
    // partners); kRecall's end is not known in advance.
    const bool enough = options_.stop_rule == AdaptiveStopRule::kEnough;
    progress_ = std::make_unique<ProgressLogger>(
        enough ? image_ids_.size() : 0,
        label_ + " rounds",
        enough ? "images with " + std::to_string(options_.min_strong_partners) +
                     " strong partners"
               : "pairs attempted");
  }
  const bool connectivity = next_connectivity_;
  for (const int c : next_) {
    Candidate& candidate = candidates_[c];
    candidate.state = Candidate::State::kPending;
    candidate.bridge = next_bridging_;
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
  round.bridging = next_bridging_;
  round.num_guarantee = next_guarantee_;
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
  if (candidate.state != Candidate::State::kObserved || !candidate.verified ||
      candidate.num_inliers < static_cast<size_t>(strong_cut_)) {
    return false;
  }
  if (rejected_ &&
      rejected_(image_ids_[candidate.row1], image_ids_[candidate.row2])) {
    return false;
  }
  if (options_.stop_rule != AdaptiveStopRule::kEnough) return true;
  return IsRelativelyStrong(candidate.num_inliers,
                            best_inliers_[candidate.row1],
                            best_inliers_[candidate.row2],
                            options_.relative_strength);
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
  Connectivity(&round.num_connected, &round.num_components);
  LogRound(round);
  if (progress_) {
    progress_->Update(options_.stop_rule == AdaptiveStopRule::kEnough
                          ? round.num_connected
                          : round.total_attempted);
  }
}

void AdaptivePairGenerator::LogRound(const AdaptiveRound& round) const {
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
  char consecutive[16];
  std::snprintf(consecutive, sizeof(consecutive), "%+.1f", consecutive_offset_);
  std::string connected;
  if (options_.stop_rule == AdaptiveStopRule::kEnough) {
    connected = "; " + std::to_string(round.num_connected) + " of " +
                std::to_string(image_ids_.size()) + " images with " +
                std::to_string(options_.min_strong_partners) +
                " strong partners, " + std::to_string(round.num_components) +
                " strong components";
    if (round.num_guarantee > 0) {
      connected += ", " + std::to_string(round.num_guarantee) +
                   " pairs for weakly connected images";
    }
  }
  LOG(INFO) << label_ << " round " << round.round
            << (round.probe          ? " (probe)"
                : round.connectivity ? " (connectivity)"
                : round.bridging     ? " (bridging)"
                                     : "")
            << ": " << round.num_pairs << " pairs attempted (calibrated yield "
            << yield << "), " << round.num_verified << " verified, "
            << round.num_strong << " strong (cut " << round.strong_cut
            << " inliers); " << round.total_attempted << " attempted, "
            << round.total_strong << " strong in all; support offsets "
            << offsets << ", consecutive " << consecutive << connected << "; "
            << seconds << " s";
}

void AdaptivePairGenerator::Connectivity(size_t* num_connected,
                                         size_t* num_components) const {
  *num_connected = 0;
  for (const std::vector<int>& list : strong_neighbours_) {
    if (static_cast<int>(list.size()) >= options_.min_strong_partners) {
      ++*num_connected;
    }
  }
  *num_components = CountComponents(strong_neighbours_);
}

void AdaptivePairGenerator::Refit() {
  std::vector<size_t> verified_inliers;
  for (const int c : yielded_) {
    const Candidate& candidate = candidates_[c];
    if (candidate.state == Candidate::State::kObserved && candidate.verified) {
      verified_inliers.push_back(candidate.num_inliers);
    }
  }
  strong_cut_ = LearnStrongInlierCut(verified_inliers,
                                     options_.min_strong_inliers,
                                     options_.max_strong_inliers);
  std::fill(best_inliers_.begin(), best_inliers_.end(), 0);
  for (const int c : yielded_) {
    const Candidate& candidate = candidates_[c];
    if (candidate.state != Candidate::State::kObserved || !candidate.verified ||
        (rejected_ &&
         rejected_(image_ids_[candidate.row1], image_ids_[candidate.row2]))) {
      continue;
    }
    for (const int row : {candidate.row1, candidate.row2}) {
      best_inliers_[row] = std::max(best_inliers_[row], candidate.num_inliers);
    }
  }
  std::fill(failures_.begin(), failures_.end(), 0);
  for (const int c : yielded_) {
    const Candidate& candidate = candidates_[c];
    if (candidate.state != Candidate::State::kObserved || IsStrong(candidate)) {
      continue;
    }
    ++failures_[candidate.row1];
    ++failures_[candidate.row2];
  }
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
  FitOffsets();
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
  size_t num_explore = std::min(
      rest.size(),
      static_cast<size_t>(std::ceil(options_.exploration_fraction *
                                    static_cast<double>(block.size()))));
  if (options_.max_exploration_pairs > 0) {
    num_explore = std::min(num_explore,
                           static_cast<size_t>(options_.max_exploration_pairs));
  }
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

size_t AdaptivePairGenerator::Budget() const {
  if (options_.max_num_pairs <= 0) return candidates_.size();
  const size_t max = static_cast<size_t>(options_.max_num_pairs);
  return yielded_.size() >= max ? 0 : max - yielded_.size();
}

size_t AdaptivePairGenerator::RoundSize() const {
  return options_.round_size > 0 ? static_cast<size_t>(options_.round_size)
                                 : std::max<size_t>(50, image_ids_.size());
}

std::vector<int> AdaptivePairGenerator::LaterRound() const {
  next_yield_ = -1;
  next_probe_ = false;
  next_connectivity_ = false;
  next_bridging_ = false;
  next_guarantee_ = 0;
  const size_t budget = Budget();
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
  const bool enough = options_.stop_rule == AdaptiveStopRule::kEnough;
  const std::vector<int> uncapped = untried;
  if (enough && options_.max_strong_partners > 0) {
    const size_t cap = static_cast<size_t>(options_.max_strong_partners);
    std::vector<int> wanted;
    for (const int c : untried) {
      if (strong_neighbours_[candidates_[c].row1].size() < cap ||
          strong_neighbours_[candidates_[c].row2].size() < cap) {
        wanted.push_back(c);
      }
    }
    untried.swap(wanted);
  }
  const size_t round_size = std::min(RoundSize(), budget);
  std::vector<int> block;
  for (const int c : untried) {
    if (block.size() >= round_size ||
        probability[c] < options_.min_pair_yield) {
      break;
    }
    block.push_back(c);
  }
  const AdaptiveRound& last = rounds_.back();
  const double last_yield = last.num_pairs == 0
                                ? 0.0
                                : static_cast<double>(last.num_strong) /
                                      static_cast<double>(last.num_pairs);
  // kEnough probes only while the last round still connected the
  // collection: more images with enough strong partners, or fewer strong
  // components, than after the round before it.
  const size_t before_connected =
      rounds_.size() >= 2 ? rounds_[rounds_.size() - 2].num_connected : 0;
  const size_t before_components =
      rounds_.size() >= 2 ? rounds_[rounds_.size() - 2].num_components
                          : image_ids_.size();
  const bool connected_more = last.num_connected > before_connected ||
                              last.num_components < before_components;
  if (block.empty() && last_yield >= options_.min_pair_yield &&
      (!enough || connected_more)) {
    // Probe: the last round verified well, so the candidates just below
    // it are tried rather than trusted to the extrapolated calibration.
    const size_t probe_size =
        std::min(round_size, std::max<size_t>(10, image_ids_.size() / 2));
    for (const int c : untried) {
      if (block.size() >= probe_size) break;
      block.push_back(c);
    }
    next_probe_ = !block.empty();
  }
  if (enough) {
    std::vector<uint8_t> taken(candidates_.size(), 0);
    for (const int c : block) taken[c] = 1;
    const std::vector<int> guarantee =
        GuaranteeBlock(untried, taken, budget - block.size());
    next_guarantee_ = guarantee.size();
    block.insert(block.end(), guarantee.begin(), guarantee.end());
    if (block.empty()) {
      block = BridgeBlock(uncapped, budget);
      next_bridging_ = !block.empty();
    }
  } else if (block.empty()) {
    block = ConnectivityBlock(untried, budget);
    next_connectivity_ = !block.empty();
  }
  if (!block.empty()) {
    double sum = 0;
    for (const int c : block) sum += probability[c];
    next_yield_ = sum / static_cast<double>(block.size());
    return block;
  }
  std::string enough_reason;
  if (enough) {
    enough_reason = ", and every image has " +
                    std::to_string(options_.min_strong_partners) +
                    " strong partners or has tried " +
                    std::to_string(options_.image_patience) +
                    " candidates without one";
    if (options_.component_patience > 0) {
      enough_reason +=
          ", and every model the strong pairs grow has spent its " +
          std::to_string(options_.component_patience) +
          " attempts at joining another or has no candidate "
          "leading out of it";
    }
  }
  if (enough && options_.max_strong_partners > 0) {
    enough_reason += " (pairs of two images with " +
                     std::to_string(options_.max_strong_partners) +
                     " strong partners are not asked for)";
  }
  LOG(INFO) << label_ << ": finished after " << rounds_.size()
            << " rounds; no candidate left with a calibrated probability "
               "of a strong verification >= "
            << options_.min_pair_yield << enough_reason
            << (budget == 0 ? " within max_num_pairs" : "");
  return block;
}

}  // namespace colmap_gcn
