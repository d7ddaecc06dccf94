// Fuzzes the hloc HDF5 global-descriptor importer. The bytes go to a .h5
// file that libhdf5 (not instrumented) parses; our code must turn every
// failure it reports into an Error.

#include "fuzz_utils.h"
#include "retrieval/descriptor_import.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path =
      colmap_gcn::fuzz::WriteScratchFile("descriptors.h5", data, size);
  try {
    const colmap_gcn::ImportedDescriptors imported =
        colmap_gcn::ReadHdf5GlobalDescriptors(path);
    if (imported.names.size() != static_cast<size_t>(imported.vectors.rows()))
      __builtin_trap();
  } catch (const colmap_gcn::Error& error) {
    colmap_gcn::fuzz::Rejected(error);
  }
  return 0;
}
