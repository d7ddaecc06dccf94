#include "util/file.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "util/error.h"

namespace colmap_gcn {

namespace fs = std::filesystem;

bool ExistsFile(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

bool ExistsDir(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

std::string JoinPaths(const std::string& a, const std::string& b) {
  return (fs::path(a) / fs::path(b)).string();
}

void CreateDirIfNotExists(const std::string& path) {
  std::error_code ec;
  fs::create_directories(path, ec);
  if (ec || !ExistsDir(path)) {
    ThrowError("cannot create directory ", path, ": ", ec.message());
  }
}

std::string ReadTextFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    ThrowError("cannot read ", path);
  }
  std::ostringstream contents;
  contents << file.rdbuf();
  return contents.str();
}

void WriteFileAtomically(const std::string& path, const std::string& contents) {
  const std::string tmp_path = path + ".tmp";
  {
    std::ofstream file(tmp_path, std::ios::binary | std::ios::trunc);
    if (!file) {
      ThrowError("cannot write ", tmp_path);
    }
    file << contents;
    if (!file.flush()) {
      ThrowError("cannot write ", tmp_path);
    }
  }
  std::error_code ec;
  fs::rename(tmp_path, path, ec);
  if (ec) {
    fs::remove(tmp_path, ec);
    ThrowError("cannot replace ", path, ": ", ec.message());
  }
}

TemporaryDirectory::TemporaryDirectory(const std::string& prefix) {
  std::string pattern =
      (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (mkdtemp(buffer.data()) == nullptr) {
    ThrowError("cannot create a temporary directory from ", pattern);
  }
  path_ = buffer.data();
}

TemporaryDirectory::~TemporaryDirectory() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

}  // namespace colmap_gcn
