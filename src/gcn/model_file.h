#pragma once

#include <cstdint>
#include <string>

#include "gcn/gcn_model.h"

namespace colmap_gcn {

// GCN model file (".gcnmodel"), little-endian, version 1:
//
//   offset 0   char[8]  magic "CGCNMODL"
//          8   u32      format version (1)
//         12   u32      reserved (0)
//         16   u64      payload size P
//         24   u8[P]    payload: sections, each
//                         char[4] tag, u64 length L, u8[L] body
//       24+P   u64      FNV-1a 64 checksum of the payload bytes
//
// Sections (all required except FEAT, STRC and NOTE; unknown tags are
// skipped so later versions can add sections):
//   EMBD  embedding configuration: str type, i32 D, str blob (opaque bytes)
//   NETS  network shape: i32 input_dim, i32 L, i32 gcn_dims[L], i32 fc_dim,
//         i32 aggregation (0 symmetric, 1 row-normalised)
//   FEAT  i32 node feature scaling (1 query scale); absent = none
//   STRC  i32 structural node features (1 k-reciprocal, 2 k-reciprocal
//         only); absent = none.
//         input_dim = D + 4 (1) or 5 (2, without D)
//   NORM  input standardisation: f32 shift[input_dim], f32 scale[input_dim]
//   WGTS  u64 count, f32 parameters[count] in GcnParameterLayout order
//   INFO  f32 tau_mo, f32 tau_ct, i32 test_k1, i32 test_k2, i32 test_u,
//         f32 threshold
//   NOTE  str notes
// where str = u64 length + bytes. The file is written atomically.
constexpr uint32_t kGcnModelFormatVersion = 1;

std::string SerializeGcnModel(const GcnModel& model);

// `source` names the data in error messages (e.g. the path). Throws a
// one-line Error for truncated, foreign, corrupt or inconsistent data.
GcnModel DeserializeGcnModel(const std::string& bytes,
                             const std::string& source);

void WriteGcnModel(const std::string& path, const GcnModel& model);
GcnModel ReadGcnModel(const std::string& path);

uint64_t Fnv1a64(const char* data, size_t size);

}  // namespace colmap_gcn
