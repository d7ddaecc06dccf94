#include "controllers/gcn_matching.h"

#include <cstdio>
#include <filesystem>
#include <set>

#include "controllers/colmap_runner.h"
#include "scene/database_copy.h"
#include "scene/database_validation.h"
#include "scene/database_working_copy.h"
#include "util/error.h"
#include "util/file.h"
#include "util/file_lock.h"
#include "util/interrupt.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/string.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

// The files a gcn_matcher run may create: the pairs file, COLMAP's log and
// whatever it keeps beside the database ("<database>.*": embedding caches,
// the working copy; "<database>-wal"/"-shm"). A run that fails before COLMAP
// wrote anything removes those it created: nothing is there to resume. The
// empty "-wal"/"-shm" that SQLite leaves beside a database it only read go
// whenever the run ends.
class RunFiles {
 public:
  RunFiles(const std::string& database_path,
           const std::string& real_database_path,
           const std::vector<std::string>& outputs)
      : database_path_(real_database_path) {
    for (const std::string& path : outputs) {
      if (!ExistsFile(path)) new_paths_.push_back(path);
    }
    for (const std::string& path : {database_path, real_database_path}) {
      for (const std::string& side_path : SideFiles(path)) {
        existing_.insert(side_path);
      }
    }
  }

  void RemoveCreated() const {
    std::error_code ec;
    for (const std::string& path : new_paths_) {
      std::filesystem::remove(path, ec);
    }
    for (const std::string& path : SideFiles(database_path_)) {
      if (existing_.count(path) == 0 && !IsSqliteSideFile(path)) {
        std::filesystem::remove(path, ec);
      }
    }
    RemoveSqliteSideFiles();
  }

  void RemoveSqliteSideFiles() const {
    RemoveEmptySqliteSideFiles(database_path_);
  }

 private:
  // Regular files "<path>.*" and "<path>-*" beside path.
  static std::vector<std::string> SideFiles(const std::string& path) {
    const std::filesystem::path file(path);
    const std::string name = file.filename().string();
    const std::filesystem::path dir =
        file.has_parent_path() ? file.parent_path() : ".";
    std::vector<std::string> paths;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
      const std::string other = entry.path().filename().string();
      if (other.size() > name.size() && StringStartsWith(other, name) &&
          (other[name.size()] == '.' || other[name.size()] == '-') &&
          entry.is_regular_file(ec)) {
        paths.push_back((dir / other).string());
      }
    }
    return paths;
  }

  bool IsSqliteSideFile(const std::string& path) const {
    return path == database_path_ + "-wal" || path == database_path_ + "-shm";
  }

  std::string database_path_;
  std::vector<std::string> new_paths_;
  std::set<std::string> existing_;
};

}  // namespace

void GcnMatchingOptions::Matching::Check() const {
  CHECK_OPTION_GE(block_size, 1);
  CHECK_OPTION_GE(min_num_inliers, 0);
}

GcnMatchingOptions::GcnMatchingOptions()
    : pairing(kDefaultPairing), generators(PairGenerators().DefaultOptions()) {}

void GcnMatchingOptions::Check() const {
  const std::vector<std::string> names = PairGenerators().Names();
  CHECK_OPTION(pairing,
               PairGenerators().Has(pairing),
               "be one of " + StringJoin(names, "|"));
  PairGenerators().Check(pairing, generators);
  matching.Check();
  lookalike_filter.Check();
}

void CheckOutputFolder(const std::string& path) {
  if (path.empty()) return;
  const std::filesystem::path parent =
      std::filesystem::absolute(std::filesystem::path(path)).parent_path();
  std::error_code ec;
  if (!std::filesystem::is_directory(parent, ec)) {
    ThrowError(
        "cannot write ", path, ": folder ", parent.string(), " does not exist");
  }
}

std::unique_ptr<PairGenerator> CreatePairGenerator(
    const GcnMatchingOptions& options, const Database& database) {
  options.Check();
  PairGeneratorContext context(database);
  context.colmap_log_path = options.matching.colmap_log_path;
  context.verbose = options.matching.verbose;
  return PairGenerators().Create(options.pairing, options.generators, context);
}

namespace {

// RunGcnMatching's work once the database is locked; *colmap is set before
// COLMAP is first run.
GcnMatchingReport ChooseAndMatchPairs(const std::string& database_path,
                                      const std::string& log_path,
                                      const GcnMatchingOptions& options,
                                      std::unique_ptr<ColmapRunner>* colmap) {
  // COLMAP is looked for before minutes of pairing, not after.
  ColmapRunnerOptions runner_options;
  runner_options.log_path = log_path;
  runner_options.verbose = options.matching.verbose;
  *colmap = std::make_unique<ColmapRunner>(runner_options);

  GcnMatchingReport report;
  report.pairing = options.pairing;
  const Timer pairing_timer;
  // Every generator keeps what it needs from the database, which is closed
  // before COLMAP replaces it.
  std::unique_ptr<PairGenerator> generator;
  {
    const Database database(database_path);
    // Before any working copy: COLMAP aborts on such a database, and every
    // rerun would abort the same way.
    ValidateDatabaseForColmap(database);
    report.num_images = database.NumImages();
    if (report.num_images == 0) {
      ThrowError(database_path,
                 " has 0 images; run colmap feature_extractor first");
    }
    if (report.num_images < 2) {
      ThrowError(database_path,
                 " has 1 image; matching needs at least 2 (add images and "
                 "extract their features into it)");
    }
    if (database.NumDescriptors() == 0) {
      ThrowError(database_path,
                 " has ",
                 report.num_images,
                 " images but no descriptors; run colmap feature_extractor "
                 "first");
    }
    generator = CreatePairGenerator(options, database);
    StopPointForTests("pairing");
  }
  const std::string warning = generator->Warning();
  if (!warning.empty()) LOG(WARNING) << warning;
  report.pairing_seconds = pairing_timer.ElapsedSeconds();

  PairMatchingOptions matching_options;
  matching_options.pairs_path = options.matching.pairs_path;
  matching_options.colmap_args = options.colmap_args;
  matching_options.block_size = options.matching.block_size;
  matching_options.min_num_inliers = options.matching.min_num_inliers;
  matching_options.lookalikes_unverified = options.filter_lookalikes;
  matching_options.lookalike_filter = options.lookalike_filter;
  LOG(INFO) << options.pairing << " pairing of " << report.num_images
            << " images"
            << (generator->UsesVerification()
                    ? " in rounds, each matched and verified before the next"
                    : "")
            << "; matching with COLMAP " << (*colmap)->Version();
  report.matching = MatchPairGenerator(
      **colmap, database_path, generator.get(), matching_options);
  report.pairing_seconds += report.matching.generator_seconds;
  if (report.matching.num_attempted_pairs == 0) {
    LOG(WARNING) << options.pairing
                 << " pairing chose no pairs, so nothing was matched";
  }
  return report;
}

}  // namespace

GcnMatchingReport RunGcnMatching(const std::string& database_path,
                                 const GcnMatchingOptions& options) {
  options.Check();
  const std::string log_path = options.matching.colmap_log_path.empty()
                                   ? database_path + ".colmap.log"
                                   : options.matching.colmap_log_path;
  CheckOutputFolder(log_path);
  CheckOutputFolder(options.matching.pairs_path);
  // Refused before minutes of pairing: a database we cannot replace, or one
  // that another gcn_matcher is working on (the lock spans the whole run).
  const std::string real_path = ResolveDatabasePath(database_path);
  // A crashed writer's rollback journal makes every read-only open fail; one
  // that cannot be rolled back is named before the file's permissions.
  RecoverHotJournal(database_path);
  CheckDatabaseWritable(real_path);
  const ScopedFileLock lock(DatabaseLockPath(real_path), database_path);
  const RunFiles run_files(
      database_path,
      real_path,
      {log_path,
       options.matching.pairs_path.empty() ? database_path + ".pairs.txt"
                                           : options.matching.pairs_path});
  std::unique_ptr<ColmapRunner> colmap;
  try {
    GcnMatchingReport report =
        ChooseAndMatchPairs(database_path, log_path, options, &colmap);
    if (options.filter_lookalikes) {
      PairFilterOptions filter_options = options.lookalike_filter;
      filter_options.min_num_inliers = options.matching.min_num_inliers;
      const PairFilterReport filter =
          FilterLookalikePairs(database_path, filter_options);
      report.filtered_lookalikes = true;
      report.num_lookalike_pairs = filter.num_rejected;
      report.filter_seconds = filter.seconds;
    }
    run_files.RemoveSqliteSideFiles();
    return report;
  } catch (...) {
    if (colmap == nullptr || colmap->NumRuns() == 0) {
      run_files.RemoveCreated();
    } else {
      run_files.RemoveSqliteSideFiles();
    }
    throw;
  }
}

void PrintGcnMatchingReport(const GcnMatchingReport& report) {
  std::printf("%-12s %8s %8s %8s %8s %10s %10s\n",
              "pairing",
              "images",
              "TAM",
              "UM",
              "UM/TAM",
              "pairing_s",
              "matching_s");
  std::printf("%-12s %8zu %8zu %8zu %8.3f %10.2f %10.2f\n",
              report.pairing.c_str(),
              report.num_images,
              report.matching.num_attempted_pairs,
              report.matching.num_verified_pairs,
              report.matching.UsefulRatio(),
              report.pairing_seconds,
              report.matching.matching_seconds);
  if (report.matching.num_already_matched > 0) {
    std::printf("(%zu of the pairs were already matched in the database)\n",
                report.matching.num_already_matched);
  }
  if (report.filtered_lookalikes) {
    std::printf(
        "look-alike filter: %zu verified pairs hidden from the mapper "
        "(%.2f s; colmap gcn_pair_filter --restore 1 puts them back)\n",
        report.num_lookalike_pairs,
        report.filter_seconds);
  }
  std::printf("pairs written to %s\n", report.matching.pairs_path.c_str());
}

}  // namespace colmap_gcn
