#pragma once

// Helpers shared by the fuzz targets: readers that take a path get the
// fuzzer's bytes through files in one scratch directory per process (on
// /dev/shm when it exists, so iterations do not touch the disk).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace colmap_gcn {
namespace fuzz {

class ScratchDirectory {
 public:
  ScratchDirectory() {
    path_ = (access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp") +
            std::string("/colmap_gcn_fuzz-XXXXXX");
    if (mkdtemp(path_.data()) == nullptr) abort();
  }
  ~ScratchDirectory() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::string& Path() const { return path_; }

 private:
  std::string path_;
};

inline const std::string& ScratchDir() {
  static const ScratchDirectory dir;
  return dir.Path();
}

// Writes bytes to <scratch>/<name> and returns the path.
inline std::string WriteScratchFile(const std::string& name,
                                    const uint8_t* data,
                                    size_t size) {
  const std::string path = ScratchDir() + "/" + name;
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(reinterpret_cast<const char*>(data),
             static_cast<std::streamsize>(size));
  file.close();
  if (!file) abort();
  return path;
}

inline void RemoveScratchFile(const std::string& name) {
  unlink((ScratchDir() + "/" + name).c_str());
}

// Inputs that hold several files separate them with this line, so that
// mutations of one file keep the others intact.
constexpr char kSeparator[] = "\n--next-file--\n";

inline std::vector<std::string> SplitFiles(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::string separator = kSeparator;
  std::vector<std::string> parts;
  size_t begin = 0;
  while (true) {
    const size_t at = bytes.find(separator, begin);
    if (at == std::string::npos) {
      parts.push_back(bytes.substr(begin));
      return parts;
    }
    parts.push_back(bytes.substr(begin, at - begin));
    begin = at + separator.size();
  }
}

inline std::string WriteScratchFile(const std::string& name,
                                    const std::string& bytes) {
  return WriteScratchFile(
      name, reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}

// Called for every Error a reader throws: rejecting malformed input is the
// contract. With COLMAP_GCN_FUZZ_EXPECT_VALID set (scripts/fuzz.sh checks
// the seed corpus this way) a rejection aborts, so seeds that no longer
// parse are noticed.
inline void Rejected(const std::exception& error) {
  static const bool expect_valid =
      std::getenv("COLMAP_GCN_FUZZ_EXPECT_VALID") != nullptr;
  if (expect_valid) {
    std::fprintf(stderr, "seed rejected: %s\n", error.what());
    abort();
  }
}

}  // namespace fuzz
}  // namespace colmap_gcn
