#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace colmap_gcn {

// The per-image embedding caches' file: char[8] magic, the caller's header
// bytes (version, model identity), uint32 dim, uint64 num_entries, then per
// entry uint64 key and float32[dim], then uint64 HashBytes of everything
// before. A cache is only an accelerator, so reading never throws.
typedef std::unordered_map<uint64_t, Eigen::RowVectorXf> KeyedRows;

// The rows of `path` if it exists and matches magic, header and dim exactly
// and its hash checks out; otherwise none.
KeyedRows ReadKeyedRowFile(const std::string& path,
                           const char (&magic)[8],
                           const std::string& header,
                           int dim);

// Writes the rows atomically; a failure (e.g. a read-only folder) only logs
// a warning naming `what`.
void WriteKeyedRowFile(
    const std::string& path,
    const char (&magic)[8],
    const std::string& header,
    int dim,
    const std::vector<std::pair<uint64_t, const float*>>& rows,
    const std::string& what);

}  // namespace colmap_gcn
