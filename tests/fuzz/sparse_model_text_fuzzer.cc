// Fuzzes COLMAP's text sparse-model reader. The input is cameras.txt,
// images.txt and points3D.txt joined by the separator line; with fewer than
// three parts points3D.txt is absent (it is optional).

#include "fuzz_utils.h"
#include "scene/reconstruction.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<std::string> parts =
      colmap_gcn::fuzz::SplitFiles(data, size);
  colmap_gcn::fuzz::WriteScratchFile("cameras.txt", parts[0]);
  colmap_gcn::fuzz::WriteScratchFile("images.txt",
                                     parts.size() > 1 ? parts[1] : "");
  if (parts.size() > 2) {
    colmap_gcn::fuzz::WriteScratchFile("points3D.txt", parts[2]);
  } else {
    colmap_gcn::fuzz::RemoveScratchFile("points3D.txt");
  }
  try {
    colmap_gcn::Reconstruction reconstruction;
    reconstruction.ReadText(colmap_gcn::fuzz::ScratchDir());
  } catch (const colmap_gcn::Error& error) {
    colmap_gcn::fuzz::Rejected(error);
  }
  return 0;
}
