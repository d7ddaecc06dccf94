// Fuzzes the Bundler v0.3 reader (bundle.out) and, on the same bytes, the
// 1DSfM image-list reader (list.txt).

#include "evaluation/bundler.h"
#include "fuzz_utils.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path =
      colmap_gcn::fuzz::WriteScratchFile("bundle.out", data, size);
  try {
    const colmap_gcn::BundlerFile bundle = colmap_gcn::ReadBundlerFile(path);
    for (const colmap_gcn::BundlerPoint& point : bundle.points) {
      for (const colmap_gcn::BundlerView& view : point.views) {
        if (view.camera_idx < 0 ||
            static_cast<size_t>(view.camera_idx) >= bundle.cameras.size())
          __builtin_trap();
      }
    }
  } catch (const colmap_gcn::Error& error) {
    colmap_gcn::fuzz::Rejected(error);
  }
  try {
    colmap_gcn::ReadBundlerImageList(path);
  } catch (const colmap_gcn::Error& error) {
    colmap_gcn::fuzz::Rejected(error);
  }
  return 0;
}
