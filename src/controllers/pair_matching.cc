#include "controllers/pair_matching.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <unordered_map>
#include <unordered_set>

#include "controllers/sift_matching_flags.h"
#include "pairing/pairs_io.h"
#include "scene/database.h"
#include "scene/database_working_copy.h"
#include "scene/two_view_geometry_store.h"
#include "util/error.h"
#include "util/file.h"
#include "util/file_lock.h"
#include "util/interrupt.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"
#include "util/timer.h"

namespace colmap_gcn {

size_t ProgressBlockSize(const size_t num_pairs, const int max_block_size) {
  // matches_importer reports nothing until its block is done: about ten
  // blocks show progress every 10 %, and 100 pairs keep one run's start
  // (about 0.7 s, a one-pair run) near 1 % of its matching.
  constexpr size_t kMinBlockSize = 100;
  const size_t tenth = (num_pairs + 9) / 10;
  return std::min(static_cast<size_t>(std::max(1, max_block_size)),
                  std::max(kMinBlockSize, tenth));
}

namespace {

// The COLMAP we run writes its own (3.8) layout; rows it wrote into another
// layout would not be what that layout's readers expect.
void CheckWritableByColmap(const ColmapRunner& colmap,
                           const Database& database) {
  if (database.Schema() != DatabaseSchema::kColmap38) {
    ThrowError(database.Path(),
               " has the ",
               DatabaseSchemaName(database.Schema()),
               " layout; COLMAP ",
               colmap.Version(),
               " must not write into it");
  }
}

std::unordered_map<image_pair_t, TwoViewGeometryInfo> GeometriesById(
    const Database& database) {
  std::unordered_map<image_pair_t, TwoViewGeometryInfo> by_id;
  for (const auto& info : database.ReadTwoViewGeometryInfos()) {
    by_id.emplace(info.pair_id, info);
  }
  return by_id;
}

typedef std::unordered_map<image_pair_t, TwoViewGeometryInfo> GeometryMap;

// What COLMAP was meant to write for a block, checked in the copy rather
// than trusted from its exit code: COLMAP 3.8 logs a failed SQLite write
// (a full disk) and still exits 0. Returns the copy's geometries.
GeometryMap VerifyMatchedBlock(const std::string& work_path,
                               const std::vector<DatabaseImage>& images,
                               const std::vector<ImagePair>& block) {
  const Database copy(work_path);
  GeometryMap geometries = GeometriesById(copy);
  const std::vector<image_pair_t> match_ids = copy.ReadMatchesPairIds();
  const std::unordered_set<image_pair_t> with_matches(match_ids.begin(),
                                                      match_ids.end());
  size_t num_missing = 0;
  const ImagePair* first_missing = nullptr;
  for (const ImagePair& pair : block) {
    const image_pair_t pair_id = ImagePairToPairId(pair.first, pair.second);
    if (geometries.count(pair_id) == 0 || with_matches.count(pair_id) == 0) {
      if (num_missing++ == 0) first_missing = &pair;
    }
  }
  if (num_missing > 0) {
    std::unordered_map<image_t, std::string> names;
    for (const DatabaseImage& image : images) {
      names.emplace(image.image_id, image.name);
    }
    ThrowError("colmap matches_importer exited 0 but wrote no result for ",
               num_missing,
               " of the ",
               block.size(),
               " pairs it was given (the first: ",
               names[first_missing->first],
               " ",
               names[first_missing->second],
               ")");
  }
  return geometries;
}

// The pairs in blocks of ProgressBlockSize, into the working copy: each
// block matched by MatchPairsExactly (deterministic, unlike COLMAP 3.8's
// FLANN matching) and imported raw, so COLMAP's matches_importer only
// verifies; --SiftMatching.guided_matching 1, which needs COLMAP's own
// matcher, matches with COLMAP instead. Each block commits and is verified
// before the next. A signal between blocks is reported like one during COLMAP's
// run. Returns the copy's geometries after the last block.
GeometryMap RunMatchesImporter(const ColmapRunner& colmap,
                               DatabaseWorkingCopy* working_copy,
                               const std::vector<DatabaseImage>& images,
                               const PairMatchingOptions& options,
                               const std::vector<ImagePair>& pairs,
                               bool stop_between_blocks) {
  const std::string& work_path = working_copy->Path();
  const std::string todo_path = work_path + ".pairs.txt";
  const size_t block_size = ProgressBlockSize(pairs.size(), options.block_size);
  const size_t num_blocks = (pairs.size() + block_size - 1) / block_size;
  const InterruptCheckpoints checkpoints;
  const ExactMatchingOptions matching_options =
      ExactMatchingFromFlags(options.matching, options.colmap_args);
  const int num_threads = static_cast<int>(
      SiftMatchingValue(options.colmap_args, "num_threads", -1));
  const bool colmap_matching =
      SiftMatchingValue(options.colmap_args, "guided_matching", 0) != 0;
  if (colmap_matching) {
    LOG(INFO) << "matching with COLMAP's matcher (guided matching): its "
                 "matches vary a little from run to run";
  }
  const std::vector<image_pair_t> matched_ids =
      Database(work_path).ReadMatchesPairIds();
  GeometryMap geometries;
  ProgressLogger progress(pairs.size(), "matching", "pairs");
  for (size_t block = 0; block < num_blocks; ++block) {
    const auto begin = pairs.begin() + block * block_size;
    const auto end =
        pairs.begin() + std::min(pairs.size(), (block + 1) * block_size);
    // As COLMAP stores them: the smaller id first.
    std::vector<ImagePair> block_pairs;
    for (auto it = begin; it != end; ++it) {
      block_pairs.emplace_back(std::min(it->first, it->second),
                               std::max(it->first, it->second));
    }
    // Pairs whose matches an interrupted run (or the user's database) holds
    // without a geometry are only verified: a raw import would write their
    // matches twice.
    std::vector<ImagePair> to_match;
    std::vector<ImagePair> to_verify;
    for (const ImagePair& pair : block_pairs) {
      const bool has_matches =
          std::binary_search(matched_ids.begin(),
                             matched_ids.end(),
                             ImagePairToPairId(pair.first, pair.second));
      (colmap_matching || has_matches ? to_verify : to_match).push_back(pair);
    }
    const auto import = [&](const std::string& match_type) {
      std::vector<std::string> args = {"--database_path",
                                       work_path,
                                       "--match_list_path",
                                       todo_path,
                                       "--match_type",
                                       match_type,
                                       "--SiftMatching.min_num_inliers",
                                       std::to_string(options.min_num_inliers)};
      args.insert(
          args.end(), options.colmap_args.begin(), options.colmap_args.end());
      working_copy->MarkWritten();
      colmap.Run("matches_importer", args);
    };
    try {
      ThrowIfInterrupted("before colmap matches_importer ran");
      if (!to_match.empty()) {
        std::vector<FeatureMatches> matches;
        {
          const TwoViewGeometryStore copy(work_path);
          matches =
              MatchPairsExactly(copy, to_match, matching_options, num_threads);
        }
        WriteRawMatchesFile(todo_path, to_match, matches, images);
        import("raw");
      }
      if (!to_verify.empty()) {
        WritePairsFile(todo_path, to_verify, images);
        import("pairs");
      }
      geometries = VerifyMatchedBlock(work_path, images, block_pairs);
      ThrowIfInterrupted("after colmap matches_importer ran");
    } catch (const Error& error) {
      ThrowError(error.what(),
                 " -- ",
                 working_copy->DatabasePath(),
                 " is unchanged; the pairs matched so far are kept in ",
                 work_path,
                 " and the next run resumes from there");
    }
    progress.Update(end - pairs.begin());
    if (stop_between_blocks && block + 1 < num_blocks) {
      StopPointForTests("matching");
    }
  }
  return geometries;
}

// Matches the pairs in blocks on a copy of the database that replaces it
// once everything is matched. Each block is one COLMAP run that commits
// into the copy, so an interrupted run resumes with at most one block lost.
// Returns the geometries of the database as committed.
GeometryMap MatchOnWorkingCopy(const ColmapRunner& colmap,
                               const std::string& database_path,
                               const std::vector<DatabaseImage>& images,
                               const PairMatchingOptions& options,
                               std::vector<ImagePair>* pairs,
                               PairMatchingSummary* summary) {
  DatabaseWorkingCopy working_copy(database_path);
  const std::string& work_path = working_copy.Path();
  GeometryMap geometries;
  {
    const Database copy(work_path);
    geometries = GeometriesById(copy);
  }
  if (working_copy.Resumed()) {
    const size_t num_pairs = pairs->size();
    pairs->erase(std::remove_if(pairs->begin(),
                                pairs->end(),
                                [&](const ImagePair& pair) {
                                  return geometries.count(ImagePairToPairId(
                                             pair.first, pair.second)) > 0;
                                }),
                 pairs->end());
    summary->num_already_matched += num_pairs - pairs->size();
    LOG(INFO) << "resuming the interrupted matching kept in " << work_path
              << " (" << num_pairs - pairs->size() << " of " << num_pairs
              << " pairs were matched already)";
  }
  const Timer timer;
  if (!pairs->empty()) {
    geometries = RunMatchesImporter(colmap,
                                    &working_copy,
                                    images,
                                    options,
                                    *pairs,
                                    /*stop_between_blocks=*/true);
  }
  summary->matching_seconds = timer.ElapsedSeconds();
  {
    const CriticalSection critical;
    working_copy.Commit();
  }
  std::error_code ec;
  std::filesystem::remove(work_path + ".pairs.txt", ec);
  return geometries;
}

// The pairs file of a generator's rounds: the attempted pairs in id order,
// with the generator's scores (given in yield order) when it has them.
void WriteAttemptedPairs(const std::string& path,
                         const std::vector<ImagePair>& attempted,
                         const std::vector<float>& yield_scores,
                         const std::vector<DatabaseImage>& images) {
  std::vector<size_t> order(attempted.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::vector<ImagePair> keys;
  for (const ImagePair& pair : attempted) {
    keys.emplace_back(std::min(pair.first, pair.second),
                      std::max(pair.first, pair.second));
  }
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return keys[a] < keys[b];
  });
  std::vector<ImagePair> sorted;
  std::vector<float> sorted_scores;
  for (const size_t i : order) {
    sorted.push_back(keys[i]);
    if (yield_scores.size() == attempted.size()) {
      sorted_scores.push_back(yield_scores[i]);
    }
  }
  WritePairsFile(path, sorted, images, sorted_scores);
}

}  // namespace

void PairMatchingOptions::Check() const {
  CHECK_OPTION_GE(min_num_inliers, 0);
  CHECK_OPTION_GE(block_size, 1);
}

PairMatchingSummary MatchImagePairs(const ColmapRunner& colmap,
                                    const std::string& database_path,
                                    const std::vector<ImagePair>& pairs,
                                    const PairMatchingOptions& options) {
  options.Check();
  if (!options.scores.empty() && options.scores.size() != pairs.size()) {
    ThrowError("matching options: ",
               options.scores.size(),
               " scores for ",
               pairs.size(),
               " pairs");
  }
  // Held for the whole run: a second gcn_matcher would otherwise resume
  // this run's copy while COLMAP still writes into it.
  const ScopedFileLock lock(
      DatabaseLockPath(ResolveDatabasePath(database_path)), database_path);
  PairMatchingSummary summary;
  summary.pairs_path = options.pairs_path.empty() ? database_path + ".pairs.txt"
                                                  : options.pairs_path;
  const int min_num_inliers = options.min_num_inliers;

  std::vector<DatabaseImage> images;
  std::unordered_set<image_pair_t> pair_ids;
  std::unordered_map<image_pair_t, float> scores;
  std::vector<ImagePair> unmatched_pairs;
  GeometryMap geometries;
  {
    const Database database(database_path);
    CheckWritableByColmap(colmap, database);
    images = database.ReadAllImages();
    geometries = GeometriesById(database);
    for (size_t i = 0; i < pairs.size(); ++i) {
      const ImagePair& pair = pairs[i];
      if (pair.first == pair.second) continue;
      const image_pair_t pair_id = ImagePairToPairId(pair.first, pair.second);
      if (!options.scores.empty()) {
        float& score = scores[pair_id];
        score = std::max(score, options.scores[i]);
      }
      if (!pair_ids.insert(pair_id).second) continue;
      if (geometries.count(pair_id) > 0) {
        ++summary.num_already_matched;
      } else {
        unmatched_pairs.push_back(pair);
      }
    }
  }
  summary.num_attempted_pairs = pair_ids.size();

  // The complete set is what users inspect; COLMAP gets only what is left.
  std::vector<ImagePair> all_pairs;
  for (const image_pair_t pair_id : pair_ids) {
    all_pairs.push_back(PairIdToImagePair(pair_id));
  }
  std::sort(all_pairs.begin(), all_pairs.end());
  std::vector<float> all_scores;
  if (!options.scores.empty()) {
    for (const auto& [id1, id2] : all_pairs) {
      all_scores.push_back(scores.at(ImagePairToPairId(id1, id2)));
    }
  }
  WritePairsFile(summary.pairs_path, all_pairs, images, all_scores);

  if (!unmatched_pairs.empty()) {
    geometries = MatchOnWorkingCopy(
        colmap, database_path, images, options, &unmatched_pairs, &summary);
  }

  for (const auto& [pair_id, info] : geometries) {
    if (pair_ids.count(pair_id) > 0 &&
        IsVerifiedTwoViewGeometry(
            info.config, info.num_inliers, min_num_inliers)) {
      ++summary.num_verified_pairs;
    }
  }
  return summary;
}

namespace {

// A generator that does not use verification: all its pairs at once.
PairMatchingSummary MatchAllPairs(const ColmapRunner& colmap,
                                  const std::string& database_path,
                                  PairGenerator* generator,
                                  const PairMatchingOptions& options,
                                  std::vector<ImagePair>* pairs) {
  std::vector<ImagePair> all_pairs = generator->AllPairs();
  LOG(INFO) << all_pairs.size() << " pairs chosen";
  PairMatchingOptions scored = options;
  scored.scores = generator->Scores();
  const PairMatchingSummary summary =
      MatchImagePairs(colmap, database_path, all_pairs, scored);
  if (pairs != nullptr) *pairs = std::move(all_pairs);
  return summary;
}

// How a round's pairs verified, for Observe(), by the deterministic
// verification; `verified` collects every verified pair of the run so far.
// With options.lookalikes_unverified, the pairs the look-alike filter
// rejects among all of them reach the generator as unverified.
std::vector<PairVerification> VerifyRound(
    const std::string& work_path,
    const std::vector<ImagePair>& round_pairs,
    const PairMatchingOptions& options,
    const ExactVerificationOptions& verification_options,
    std::vector<VerifiedTwoViewGeometry>* verified) {
  const TwoViewGeometryStore copy(work_path);
  const std::vector<VerifiedTwoViewGeometry> round =
      VerifyPairsExactly(copy, round_pairs, verification_options);
  std::vector<PairVerification> verifications;
  verifications.reserve(round.size());
  for (const VerifiedTwoViewGeometry& geometry : round) {
    PairVerification verification;
    verification.image_id1 = geometry.image_id1;
    verification.image_id2 = geometry.image_id2;
    verification.config = geometry.config;
    verification.num_inliers = geometry.inliers.rows();
    verifications.push_back(verification);
    if (IsVerifiedTwoViewGeometry(geometry.config,
                                  geometry.inliers.rows(),
                                  options.min_num_inliers)) {
      verified->push_back(geometry);
    }
  }
  if (!options.lookalikes_unverified) return verifications;
  PairFilterOptions filter_options = options.lookalike_filter;
  filter_options.min_num_inliers = options.min_num_inliers;
  const std::vector<image_pair_t> rejected =
      RejectedPairIds(FindLookalikePairs(copy, *verified, filter_options));
  for (PairVerification& verification : verifications) {
    if (std::binary_search(rejected.begin(),
                           rejected.end(),
                           ImagePairToPairId(verification.image_id1,
                                             verification.image_id2))) {
      verification.config = 0;
    }
  }
  return verifications;
}

size_t CountVerifiedPairs(const std::vector<ImagePair>& pairs,
                          const GeometryMap& geometries,
                          int min_num_inliers) {
  size_t num_verified = 0;
  for (const ImagePair& pair : pairs) {
    const auto it = geometries.find(ImagePairToPairId(pair.first, pair.second));
    if (it != geometries.end() &&
        IsVerifiedTwoViewGeometry(
            it->second.config, it->second.num_inliers, min_num_inliers)) {
      ++num_verified;
    }
  }
  return num_verified;
}

}  // namespace

PairMatchingSummary MatchPairGenerator(const ColmapRunner& colmap,
                                       const std::string& database_path,
                                       PairGenerator* generator,
                                       const PairMatchingOptions& options,
                                       std::vector<ImagePair>* pairs) {
  THROW_CHECK(generator != nullptr);
  THROW_CHECK(options.scores.empty());
  if (!generator->UsesVerification()) {
    return MatchAllPairs(colmap, database_path, generator, options, pairs);
  }
  options.Check();
  const ScopedFileLock lock(
      DatabaseLockPath(ResolveDatabasePath(database_path)), database_path);
  PairMatchingSummary summary;
  summary.pairs_path = options.pairs_path.empty() ? database_path + ".pairs.txt"
                                                  : options.pairs_path;
  std::vector<DatabaseImage> images;
  {
    const Database database(database_path);
    CheckWritableByColmap(colmap, database);
    images = database.ReadAllImages();
  }

  DatabaseWorkingCopy working_copy(database_path);
  const std::string& work_path = working_copy.Path();
  GeometryMap geometries;
  {
    const Database copy(work_path);
    geometries = GeometriesById(copy);
  }
  if (working_copy.Resumed()) {
    LOG(INFO) << "resuming the interrupted matching kept in " << work_path
              << ": its " << geometries.size()
              << " matched pairs answer the rounds they were chosen in";
  }

  const ExactVerificationOptions verification_options =
      ExactVerificationFromFlags(
          options.verification, options.colmap_args, options.min_num_inliers);
  std::vector<VerifiedTwoViewGeometry> verified;
  std::vector<ImagePair> attempted;
  std::unordered_set<image_pair_t> attempted_ids;
  generator->Reset();
  Timer generator_timer;
  double generator_seconds = 0;
  while (true) {
    generator_timer.Restart();
    if (generator->HasFinished()) {
      generator_seconds += generator_timer.ElapsedSeconds();
      break;
    }
    const std::vector<ImagePair> block = generator->Next();
    generator_seconds += generator_timer.ElapsedSeconds();
    ++summary.num_rounds;
    std::vector<ImagePair> round_pairs;
    std::vector<ImagePair> todo;
    for (const ImagePair& pair : block) {
      if (pair.first == pair.second) continue;
      const image_pair_t pair_id = ImagePairToPairId(pair.first, pair.second);
      if (!attempted_ids.insert(pair_id).second) continue;
      round_pairs.push_back(pair);
      attempted.push_back(pair);
      if (geometries.count(pair_id) > 0) {
        ++summary.num_already_matched;
      } else {
        todo.push_back(pair);
      }
    }
    if (!todo.empty()) {
      const Timer timer;
      geometries = RunMatchesImporter(colmap,
                                      &working_copy,
                                      images,
                                      options,
                                      todo,
                                      /*stop_between_blocks=*/false);
      summary.matching_seconds += timer.ElapsedSeconds();
    }
    generator_timer.Restart();
    const std::vector<PairVerification> verifications = VerifyRound(
        work_path, round_pairs, options, verification_options, &verified);
    summary.verification_seconds += generator_timer.ElapsedSeconds();
    generator->Observe(verifications);
    generator_seconds += generator_timer.ElapsedSeconds();

    // What users inspect: every pair attempted so far, with its score.
    WriteAttemptedPairs(
        summary.pairs_path, attempted, generator->Scores(), images);
    if (!generator->HasFinished()) StopPointForTests("matching");
  }
  summary.generator_seconds = generator_seconds;
  LOG(INFO) << "the rounds decided on their own verification of "
            << attempted.size() << " pairs, "
            << ProgressLogger::FormatDuration(summary.verification_seconds)
            << " (matching and COLMAP's verification "
            << ProgressLogger::FormatDuration(summary.matching_seconds) << ")";
  summary.num_attempted_pairs = attempted.size();
  summary.num_verified_pairs =
      CountVerifiedPairs(attempted, geometries, options.min_num_inliers);
  {
    const CriticalSection critical;
    working_copy.Commit();
  }
  std::error_code ec;
  std::filesystem::remove(work_path + ".pairs.txt", ec);
  if (pairs != nullptr) *pairs = std::move(attempted);
  return summary;
}

}  // namespace colmap_gcn
