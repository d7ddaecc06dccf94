#include "controllers/pair_matching.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <unordered_map>
#include <unordered_set>

#include "pairing/pairs_io.h"
#include "scene/database.h"
#include "scene/database_working_copy.h"
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

// COLMAP's matches_importer on the pairs in blocks of ProgressBlockSize,
// into the working copy; each block commits and is verified before the
// next. A signal between blocks is reported like one during COLMAP's run.
// Returns the copy's geometries after the last block.
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
  GeometryMap geometries;
  ProgressLogger progress(pairs.size(), "matching", "pairs");
  for (size_t block = 0; block < num_blocks; ++block) {
    const auto begin = pairs.begin() + block * block_size;
    const auto end =
        pairs.begin() + std::min(pairs.size(), (block + 1) * block_size);
    const std::vector<ImagePair> block_pairs(begin, end);
    std::vector<std::string> args = {"--database_path",
                                     work_path,
                                     "--match_list_path",
                                     todo_path,
                                     "--match_type",
                                     "pairs",
                                     "--SiftMatching.min_num_inliers",
                                     std::to_string(options.min_num_inliers)};
    args.insert(
        args.end(), options.colmap_args.begin(), options.colmap_args.end());
    try {
      ThrowIfInterrupted("before colmap matches_importer ran");
      WritePairsFile(todo_path, block_pairs, images);
      working_copy->MarkWritten();
      colmap.Run("matches_importer", args);
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

// How a round's pairs verified, for Observe(); a pair COLMAP kept no row
// for stays at PairVerification's defaults (unverified).
// Reports the pairs the look-alike filter rejects, among all verified pairs
// of the working copy so far, as unverified.
void MarkLookalikesUnverified(const std::string& work_path,
                              const PairMatchingOptions& options,
                              std::vector<PairVerification>* verifications) {
  PairFilterOptions filter_options = options.lookalike_filter;
  filter_options.min_num_inliers = options.min_num_inliers;
  const TwoViewGeometryStore copy(work_path);
  const std::vector<image_pair_t> rejected =
      RejectedPairIds(FindLookalikePairs(copy, filter_options));
  for (PairVerification& verification : *verifications) {
    if (std::binary_search(rejected.begin(),
                           rejected.end(),
                           ImagePairToPairId(verification.image_id1,
                                             verification.image_id2))) {
      verification.config = 0;
    }
  }
}

std::vector<PairVerification> Verifications(const std::vector<ImagePair>& pairs,
                                            const GeometryMap& geometries) {
  std::vector<PairVerification> verifications;
  verifications.reserve(pairs.size());
  for (const ImagePair& pair : pairs) {
    PairVerification verification;
    verification.image_id1 = pair.first;
    verification.image_id2 = pair.second;
    const auto it = geometries.find(ImagePairToPairId(pair.first, pair.second));
    if (it != geometries.end()) {
      verification.config = it->second.config;
      verification.num_inliers = it->second.num_inliers;
    }
    verifications.push_back(verification);
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
    std::vector<PairVerification> verifications =
        Verifications(round_pairs, geometries);
    if (options.lookalikes_unverified) {
      MarkLookalikesUnverified(work_path, options, &verifications);
    }
    generator_timer.Restart();
    generator->Observe(verifications);
    generator_seconds += generator_timer.ElapsedSeconds();

    // What users inspect: every pair attempted so far, with its score.
    WriteAttemptedPairs(
        summary.pairs_path, attempted, generator->Scores(), images);
    if (!generator->HasFinished()) StopPointForTests("matching");
  }
  summary.generator_seconds = generator_seconds;
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
