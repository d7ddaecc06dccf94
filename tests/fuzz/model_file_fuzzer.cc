// Fuzzes the GCN model-file reader (DeserializeGcnModel via ReadGcnModel).
// The FNV-1a checksum would stop almost every mutation at the header, so an
// input whose reserved header byte 12 is odd has its payload size and
// checksum fixed up first; the fuzzer then reaches the section parsers.

#include <cstring>

#include "fuzz_utils.h"
#include "gcn/model_file.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (bytes.size() >= 32 && (bytes[12] & 1)) {
    const uint64_t payload_size = bytes.size() - 32;
    std::memcpy(&bytes[16], &payload_size, 8);
    const uint64_t checksum =
        colmap_gcn::Fnv1a64(bytes.data() + 24, payload_size);
    std::memcpy(&bytes[24 + payload_size], &checksum, 8);
  }
  const std::string path =
      colmap_gcn::fuzz::WriteScratchFile("model.gcnmodel", bytes);
  try {
    const colmap_gcn::GcnModel model = colmap_gcn::ReadGcnModel(path);
    // A model that loads must be self-consistent.
    model.Check();
  } catch (const colmap_gcn::Error& error) {
    colmap_gcn::fuzz::Rejected(error);
  }
  return 0;
}
