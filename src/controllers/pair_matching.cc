#include "controllers/pair_matching.h"

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <unordered_map>
#include <unordered_set>

#include "feature/pairs_io.h"
#include "scene/database.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_manager.h"
#include "util/string.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

namespace fs = std::filesystem;

// Identifies the state of the user's database so that a partial copy is only
// resumed when the original has not changed since the copy was made.
std::string FileFingerprint(const std::string& path) {
  struct stat info;
  if (stat(path.c_str(), &info) != 0) {
    ThrowError("cannot stat ", path);
  }
  return std::to_string(info.st_size) + " " +
         std::to_string(info.st_mtim.tv_sec) + "." +
         std::to_string(info.st_mtim.tv_nsec);
}

std::unordered_map<image_pair_t, TwoViewGeometryInfo> GeometriesById(
    const Database& database) {
  std::unordered_map<image_pair_t, TwoViewGeometryInfo> by_id;
  for (const auto& info : database.ReadTwoViewGeometryInfos()) {
    by_id.emplace(info.pair_id, info);
  }
  return by_id;
}

// Prepares the working copy; returns true when an earlier partial run is
// resumed.
bool PrepareWorkingCopy(const std::string& database_path,
                        const std::string& work_path) {
  const std::string source_path = work_path + ".source";
  const std::string fingerprint = FileFingerprint(database_path);
  if (ExistsFile(work_path) && ExistsFile(source_path) &&
      StringTrim(ReadTextFile(source_path)) == fingerprint) {
    return true;
  }
  std::error_code ec;
  fs::copy_file(
      database_path, work_path, fs::copy_options::overwrite_existing, ec);
  if (ec) {
    fs::remove(work_path, ec);
    ThrowError(
        "cannot copy ", database_path, " to ", work_path, ": ", ec.message());
  }
  WriteFileAtomically(source_path, fingerprint + "\n");
  return false;
}

}  // namespace

bool PairMatchingOptions::Check() const { return min_num_inliers >= 0; }

PairMatchingSummary MatchImagePairs(const ColmapRunner& colmap,
                                    const std::string& database_path,
                                    const std::vector<ImagePair>& pairs,
                                    const PairMatchingOptions& options) {
  if (!options.Check()) {
    ThrowError("invalid matching options: min_num_inliers must be >= 0");
  }
  if (!options.scores.empty() && options.scores.size() != pairs.size()) {
    ThrowError("matching options: ",
               options.scores.size(),
               " scores for ",
               pairs.size(),
               " pairs");
  }
  PairMatchingSummary summary;
  summary.pairs_path = options.pairs_path.empty() ? database_path + ".pairs.txt"
                                                  : options.pairs_path;
  const int min_num_inliers = IntArgument(options.colmap_args,
                                          "SiftMatching.min_num_inliers",
                                          options.min_num_inliers);

  std::vector<DatabaseImage> images;
  std::unordered_set<image_pair_t> pair_ids;
  std::unordered_map<image_pair_t, float> scores;
  std::vector<ImagePair> unmatched_pairs;
  {
    const Database database(database_path);
    if (database.Schema() != DatabaseSchema::kColmap38) {
      ThrowError(database_path,
                 " has the ",
                 DatabaseSchemaName(database.Schema()),
                 " layout; COLMAP ",
                 colmap.Version(),
                 " must not write into it");
    }
    images = database.ReadAllImages();
    const auto geometries = GeometriesById(database);
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
    const std::string work_path = database_path + ".gcn-partial";
    const bool resumed = PrepareWorkingCopy(database_path, work_path);
    if (resumed) {
      std::cerr << "Resuming the interrupted matching kept in " << work_path
                << "\n";
    }
    const std::string todo_path = work_path + ".pairs.txt";
    WritePairsFile(todo_path, unmatched_pairs, images);
    std::vector<std::string> args = {"--database_path",
                                     work_path,
                                     "--match_list_path",
                                     todo_path,
                                     "--match_type",
                                     "pairs"};
    args.insert(
        args.end(), options.colmap_args.begin(), options.colmap_args.end());
    const Timer timer;
    try {
      colmap.Run("matches_importer", args);
    } catch (const Error& error) {
      ThrowError(error.what(),
                 " -- ",
                 database_path,
                 " is unchanged; the partial work in ",
                 work_path,
                 " resumes on the next run");
    }
    summary.matching_seconds = timer.ElapsedSeconds();
    // Validate the result before it replaces the user's file.
    { const Database check(work_path); }
    std::error_code ec;
    fs::rename(work_path, database_path, ec);
    if (ec) {
      ThrowError("cannot replace ",
                 database_path,
                 " with ",
                 work_path,
                 ": ",
                 ec.message());
    }
    fs::remove(work_path + ".source", ec);
    fs::remove(todo_path, ec);
  }

  const Database database(database_path);
  for (const auto& [pair_id, info] : GeometriesById(database)) {
    if (pair_ids.count(pair_id) > 0 &&
        IsVerifiedTwoViewGeometry(
            info.config, info.num_inliers, min_num_inliers)) {
      ++summary.num_verified_pairs;
    }
  }
  return summary;
}

}  // namespace colmap_gcn
