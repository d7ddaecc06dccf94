#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace colmap_gcn {
namespace test {

// Writes num_images overlapping JPEG crops (width x height) of one random,
// multi-scale textured image into image_dir, shifted by (step_x, step_y)
// pixels each, so that SIFT finds many correct matches between all of them.
// Returns the file names (relative to image_dir) in the order written.
std::vector<std::string> WriteOverlappingTestImages(
    const std::string& image_dir,
    int num_images,
    int width = 640,
    int height = 480,
    int step_x = 60,
    int step_y = 45,
    uint32_t seed = 7);

// Runs the real COLMAP's CPU feature_extractor (single camera) and
// exhaustive_matcher on image_dir into a new database. Returns false and
// fills *log with COLMAP's output on failure.
bool RunColmapFeaturesAndMatching(const std::string& colmap_exe,
                                  const std::string& image_dir,
                                  const std::string& database_path,
                                  std::string* log);

// Independent reads through the sqlite3 C API (not our Database class) to
// check it against: the first column of the first row of sql as an integer,
// or 0 for no row / NULL.
int64_t QuerySqlInt(const std::string& database_path, const std::string& sql);

// Executes sql (several statements allowed) on a database, creating the file
// if needed. Throws Error on failure.
void ExecuteSql(const std::string& database_path, const std::string& sql);

// The files a writer killed after committing `sql` on database_path leaves
// behind, written to crashed_path: its committed transactions are only in
// "<crashed_path>-wal" (copied while the writer's connection is still open,
// so nothing was checkpointed). Throws Error on failure.
void LeaveCommittedDataInWal(const std::string& database_path,
                             const std::string& sql,
                             const std::string& crashed_path);

// What a writer in rollback-journal mode (journal_mode DELETE) that crashed
// inside a transaction leaves: it runs sql after BEGIN in a child process
// with a one-page cache, so changed pages reach the database file, and the
// child exits without committing. "<database_path>-journal" is then a hot
// journal. Throws Error when no journal is left.
void LeaveHotJournal(const std::string& database_path, const std::string& sql);

}  // namespace test
}  // namespace colmap_gcn
