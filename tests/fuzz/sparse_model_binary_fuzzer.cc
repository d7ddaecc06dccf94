// Fuzzes COLMAP's binary sparse-model reader. The input is cameras.bin,
// images.bin and points3D.bin joined by the separator line; missing parts
// are empty files.

#include "fuzz_utils.h"
#include "scene/reconstruction.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<std::string> parts =
      colmap_gcn::fuzz::SplitFiles(data, size);
  const char* names[3] = {"cameras.bin", "images.bin", "points3D.bin"};
  for (size_t i = 0; i < 3; ++i) {
    colmap_gcn::fuzz::WriteScratchFile(names[i],
                                       i < parts.size() ? parts[i] : "");
  }
  try {
    colmap_gcn::Reconstruction reconstruction;
    reconstruction.ReadBinary(colmap_gcn::fuzz::ScratchDir());
  } catch (const colmap_gcn::Error& error) {
    colmap_gcn::fuzz::Rejected(error);
  }
  return 0;
}
