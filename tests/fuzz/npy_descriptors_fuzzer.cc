// Fuzzes the .npy global-descriptor importer. The input is the .npy file,
// optionally followed by the separator line and its names list
// (<path>.txt); without a names part no names file exists.

#include "fuzz_utils.h"
#include "retrieval/descriptor_import.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<std::string> parts =
      colmap_gcn::fuzz::SplitFiles(data, size);
  const std::string path =
      colmap_gcn::fuzz::WriteScratchFile("descriptors.npy", parts[0]);
  if (parts.size() > 1) {
    colmap_gcn::fuzz::WriteScratchFile("descriptors.npy.txt", parts[1]);
  } else {
    colmap_gcn::fuzz::RemoveScratchFile("descriptors.npy.txt");
  }
  try {
    const colmap_gcn::ImportedDescriptors imported =
        colmap_gcn::ReadNpyGlobalDescriptors(path);
    if (imported.names.size() != static_cast<size_t>(imported.vectors.rows()))
      __builtin_trap();
  } catch (const colmap_gcn::Error& error) {
    colmap_gcn::fuzz::Rejected(error);
  }
  return 0;
}
