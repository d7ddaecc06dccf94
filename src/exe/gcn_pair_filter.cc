#include "exe/gcn_pair_filter.h"

#include <cstdio>
#include <string>

#include "controllers/gcn_matching.h"
#include "disambiguation/pair_filter.h"
#include "scene/database_copy.h"
#include "scene/database_working_copy.h"
#include "util/file_lock.h"
#include "util/option_manager.h"

namespace colmap_gcn {

int RunGcnPairFilter(int argc, char** argv) {
  std::string database_path;
  bool restore = false;
  bool dry_run = false;
  bool list_pairs = false;
  PairFilterOptions options;
  OptionManager manager(
      "gcn_pair_filter",
      "Finds look-alike (duplicate structure) pairs among a database's "
      "verified pairs and hides them from COLMAP's mapper; their rows are "
      "kept in the table gcn_lookalike_pairs, and --restore 1 puts them "
      "back.");
  manager.AddRequiredOption("database_path", &database_path);
  manager.AddDefaultOption(
      "restore", &restore, "put every hidden pair back instead of filtering");
  manager.AddDefaultOption(
      "dry_run", &dry_run, "report the decisions, change nothing");
  manager.AddDefaultOption(
      "list_pairs", &list_pairs, "print every hidden pair");
  manager.AddDefaultOption("PairFilter.backbone_neighbors",
                           &options.decision.backbone_neighbors);
  manager.AddDefaultOption("PairFilter.max_rotation_error",
                           &options.decision.max_rotation_error,
                           "degrees");
  manager.AddDefaultOption("PairFilter.check_trusted_focal",
                           &options.check_trusted_focal,
                           "check trusted (EXIF) focal lengths against the "
                           "loops of the verified graph");
  manager.AddDefaultOption(
      "PairFilter.min_evidence_inliers",
      &options.decision.min_evidence_inliers,
      "pairs with fewer inliers face the parallax test instead");
  manager.AddDefaultOption(
      "PairFilter.max_view_parallax",
      &options.decision.max_view_parallax,
      "degrees the chained rotation may turn a weak pair's inlier rays "
      "apart (with its rotation off too); 180: off");
  manager.AddDefaultOption("PairFilter.max_backbone_hops",
                           &options.decision.max_backbone_hops,
                           "0: off");
  manager.AddDefaultOption(
      "PairFilter.distinctive_share",
      &options.distinctive_share,
      "edges are ordered by their inliers in cells at most this share of "
      "each image's pairs reach");
  manager.AddDefaultOption("PairFilter.min_num_inliers",
                           &options.min_num_inliers);
  manager.AddDefaultOption("PairFilter.num_threads",
                           &options.num_threads,
                           "-1: all cores; the result does not depend on it");
  manager.AddDefaultOption("PairFilter.pairs_csv_path",
                           &options.pairs_csv_path,
                           "one line per verified pair with its decision");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] { options.Check(); });
  CheckOutputFolder(options.pairs_csv_path);
  RecoverHotJournal(database_path);
  const std::string real_path = ResolveDatabasePath(database_path);
  if (!dry_run) CheckDatabaseWritable(real_path);
  const ScopedFileLock lock(DatabaseLockPath(real_path), database_path);
  if (restore) {
    const size_t num_restored = RestoreLookalikePairs(database_path);
    std::printf("gcn_pair_filter: %zu hidden pairs restored in %s\n",
                num_restored,
                database_path.c_str());
    return 0;
  }
  PairFilterReport report;
  if (dry_run) {
    const TwoViewGeometryStore database(database_path);
    report = FindLookalikePairs(database, options);
  } else {
    report = FilterLookalikePairs(database_path, options);
  }
  PrintPairFilterReport(report, list_pairs);
  return 0;
}

}  // namespace colmap_gcn
