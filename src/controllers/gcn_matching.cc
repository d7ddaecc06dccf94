#include "controllers/gcn_matching.h"

#include <cstdio>
#include <filesystem>

#include "controllers/colmap_runner.h"
#include "scene/database_copy.h"
#include "scene/database_validation.h"
#include "scene/database_working_copy.h"
#include "util/error.h"
#include "util/file_lock.h"
#include "util/interrupt.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/string.h"
#include "util/timer.h"

namespace colmap_gcn {

void GcnMatchingOptions::Matching::Check() const {
  CHECK_OPTION_GE(block_size, 1);
}

GcnMatchingOptions::GcnMatchingOptions()
    : pairing(PairGenerators().Names().front()),
      generators(PairGenerators().DefaultOptions()) {}

void GcnMatchingOptions::Check() const {
  const std::vector<std::string> names = PairGenerators().Names();
  CHECK_OPTION(pairing,
               PairGenerators().Has(pairing),
               "be one of " + StringJoin(names, "|"));
  PairGenerators().Check(pairing, generators);
  matching.Check();
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

  ColmapRunnerOptions runner_options;
  runner_options.log_path = log_path;
  runner_options.verbose = options.matching.verbose;
  const ColmapRunner colmap(runner_options);

  PairMatchingOptions matching_options;
  matching_options.pairs_path = options.matching.pairs_path;
  matching_options.colmap_args = options.colmap_args;
  matching_options.block_size = options.matching.block_size;
  LOG(INFO) << options.pairing << " pairing of " << report.num_images
            << " images"
            << (generator->UsesVerification()
                    ? " in rounds, each matched and verified before the next"
                    : "")
            << "; matching with COLMAP " << colmap.Version();
  report.matching = MatchPairGenerator(
      colmap, database_path, generator.get(), matching_options);
  report.pairing_seconds += report.matching.generator_seconds;
  return report;
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
  std::printf("pairs written to %s\n", report.matching.pairs_path.c_str());
}

}  // namespace colmap_gcn
