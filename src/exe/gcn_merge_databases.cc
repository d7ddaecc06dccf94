#include "exe/gcn_merge_databases.h"

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "controllers/gcn_matching.h"
#include "scene/database.h"
#include "scene/database_copy.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {

int RunGcnMergeDatabases(int argc, char** argv) {
  std::string database_paths;
  std::string name_prefixes;
  std::string output_path;
  bool keep_matches = false;
  OptionManager manager(
      "gcn_merge_databases",
      "Merges COLMAP 3.8 databases into one (cameras, images, keypoints and "
      "descriptors; matches only with --keep_matches 1), image names "
      "prefixed so they stay unique.");
  manager.AddRequiredOption(
      "database_paths", &database_paths, "comma-separated databases");
  manager.AddRequiredOption(
      "output_path", &output_path, "merged database (must not exist)");
  manager.AddDefaultOption("name_prefixes",
                           &name_prefixes,
                           "comma-separated image name prefix per database; "
                           "empty: <index>/");
  manager.AddDefaultOption(
      "keep_matches",
      &keep_matches,
      "keep each database's matches and two_view_geometries (pairs across "
      "databases stay unmatched), e.g. to replay a pairing with "
      "gcn_adaptive_simulator on scenes matched alone");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  const std::vector<std::string> paths = SplitCommaList(database_paths);
  if (paths.empty()) {
    ThrowError("--database_paths lists no database");
  }
  if (ExistsFile(output_path) || ExistsDir(output_path)) {
    ThrowError("--output_path ", output_path, " exists");
  }
  CheckOutputFolder(output_path);
  for (const std::string& path : paths) RecoverHotJournal(path);
  // Written beside the output and renamed to it when complete.
  const std::string partial = output_path + ".gcn-partial";
  std::filesystem::remove(partial);
  MergeDatabases(paths, partial, SplitCommaList(name_prefixes), keep_matches);
  std::filesystem::rename(partial, output_path);
  std::cout << Database(output_path).ReadAllImages().size() << " images from "
            << paths.size() << " database(s) in " << output_path << "\n";
  return 0;
}

}  // namespace colmap_gcn
