#pragma once

#include <cstdint>
#include <set>
#include <string>

namespace colmap_gcn {
namespace test {

// The folder of the built front end, first on PATH when the e2e tests run
// it, as users do.
std::string FrontendBinDir();

// Runs `colmap <args>` through our front end with FrontendBinDir() first on
// PATH, capturing stdout+stderr into *output (if non-null); env is handed
// to env(1) first ("COLMAP_EXE=/x", "-u COLMAP_GCN_MODEL"). Returns the
// exit code.
int RunFrontend(const std::string& args,
                std::string* output = nullptr,
                const std::string& env = "");

// SQLite's integrity_check of the database at path, as the sqlite3 shell
// prints it ("ok" when sound).
std::string IntegrityCheck(const std::string& path);

// The pair ids of path's two_view_geometries rows.
std::set<int64_t> GeometryPairIds(const std::string& path);

// A scene the e2e suites share: gcn_synth's ordinary family (seed 1)
// extracted by COLMAP into a database, with the generator's intrinsics as a
// user with a calibrated camera would pass them, on one thread (COLMAP
// numbers the images in completion order and its multi-threaded extraction
// is not repeatable).
struct ExtractedScene {
  std::string scene_path;     // <dir>/scene: images/, gt/, overlaps
  std::string image_path;     // <dir>/scene/images
  std::string database_path;  // <dir>/base.db
  // The camera and extraction flags the database was extracted with, with
  // a leading space, for commands that extract themselves
  // (gcn_reconstructor).
  std::string extraction_args;
};

// Generates num_images views into dir and extracts them. A failure is a
// fatal gtest failure (check testing::Test::HasFatalFailure()).
void MakeExtractedScene(const std::string& dir,
                        int num_images,
                        ExtractedScene* scene);

}  // namespace test
}  // namespace colmap_gcn
