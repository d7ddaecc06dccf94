// Fuzzes the pairs-file reader (COLMAP 3.8's `name1 name2` format).

#include "fuzz_utils.h"
#include "pairing/pairs_io.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path =
      colmap_gcn::fuzz::WriteScratchFile("pairs.txt", data, size);
  try {
    for (const auto& [name1, name2] : colmap_gcn::ReadPairsFile(path)) {
      if (name1.empty() || name2.empty()) __builtin_trap();
    }
  } catch (const colmap_gcn::Error& error) {
    colmap_gcn::fuzz::Rejected(error);
  }
  return 0;
}
