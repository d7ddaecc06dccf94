#pragma once

#include <string>

namespace colmap_gcn {

bool ExistsFile(const std::string& path);
bool ExistsDir(const std::string& path);

std::string JoinPaths(const std::string& a, const std::string& b);

// Creates the directory and its parents; throws Error on failure.
void CreateDirIfNotExists(const std::string& path);

// Reads a whole file; throws Error naming the path on failure.
std::string ReadTextFile(const std::string& path);

// Writes to "<path>.tmp" then renames over path, so readers never see a
// half-written file.
void WriteFileAtomically(const std::string& path, const std::string& contents);

// A fresh, empty directory under the system temp dir, removed on destruction.
class TemporaryDirectory {
 public:
  explicit TemporaryDirectory(const std::string& prefix = "colmap_gcn");
  ~TemporaryDirectory();
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

  const std::string& Path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace colmap_gcn
