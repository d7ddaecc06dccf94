#include "test_utils.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace test {

const char* const kColmap38Schema = R"sql(
CREATE TABLE cameras (camera_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  model INTEGER NOT NULL, width INTEGER NOT NULL, height INTEGER NOT NULL,
  params BLOB, prior_focal_length INTEGER NOT NULL);
CREATE TABLE images (image_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  name TEXT NOT NULL UNIQUE, camera_id INTEGER NOT NULL, prior_qw REAL,
  prior_qx REAL, prior_qy REAL, prior_qz REAL, prior_tx REAL, prior_ty REAL,
  prior_tz REAL);
CREATE TABLE keypoints (image_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB);
CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB);
CREATE TABLE matches (pair_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB);
CREATE TABLE two_view_geometries (pair_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB,
  config INTEGER NOT NULL, F BLOB, E BLOB, H BLOB, qvec BLOB, tvec BLOB);
)sql";

std::string SharedDatasetsDir() {
  const char* env = std::getenv("COLMAP_GCN_SHARED_DIR");
  const std::string shared =
      env != nullptr ? env : std::string(COLMAP_GCN_SOURCE_DIR) + "/../shared";
  const std::string datasets = JoinPaths(shared, "datasets");
  return ExistsDir(datasets) ? datasets : "";
}

std::string RealColmapExe() {
  const char* env = std::getenv("COLMAP_EXE");
  if (env != nullptr && ExistsFile(env)) {
    return env;
  }
  const char* path = std::getenv("PATH");
  if (path == nullptr) {
    return "";
  }
  std::string dirs = path;
  size_t begin = 0;
  while (begin <= dirs.size()) {
    size_t end = dirs.find(':', begin);
    if (end == std::string::npos) end = dirs.size();
    const std::string candidate =
        JoinPaths(dirs.substr(begin, end - begin), "colmap");
    if (ExistsFile(candidate) && candidate != FrontendExe()) {
      return candidate;
    }
    begin = end + 1;
  }
  return "";
}

std::string FrontendExe() { return COLMAP_GCN_FRONTEND_EXE; }

int RunShell(const std::string& command, std::string* output) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) {
    return -1;
  }
  std::array<char, 4096> buffer;
  std::string captured;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    captured.append(buffer.data(), n);
  }
  const int status = pclose(pipe);
  if (output != nullptr) {
    *output = captured;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void ExpectErrorContaining(const std::function<void()>& function,
                           const std::string& expected) {
  try {
    function();
    ADD_FAILURE() << "expected an Error containing '" << expected << "'";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

void LogLines::Send(LogLevel /*level*/, const std::string& message) {
  messages_.push_back(message);
}

}  // namespace test
}  // namespace colmap_gcn
