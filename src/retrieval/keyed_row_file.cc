#include "retrieval/keyed_row_file.h"

#include <cstring>

#include "retrieval/hash.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"

namespace colmap_gcn {

KeyedRows ReadKeyedRowFile(const std::string& path,
                           const char (&magic)[8],
                           const std::string& header,
                           int dim) {
  KeyedRows entries;
  if (path.empty() || !ExistsFile(path)) return entries;
  std::string contents;
  try {
    contents = ReadTextFile(path);
  } catch (const Error&) {
    return entries;
  }
  const size_t header_size = 8 + header.size() + 4 + 8;
  if (contents.size() < header_size + 8 ||
      std::memcmp(contents.data(), magic, 8) != 0 ||
      contents.compare(8, header.size(), header) != 0) {
    return entries;
  }
  uint32_t stored_dim;
  uint64_t num_entries, stored_hash;
  std::memcpy(&stored_dim, contents.data() + 8 + header.size(), 4);
  std::memcpy(&num_entries, contents.data() + 8 + header.size() + 4, 8);
  const size_t entry_size = 8 + 4 * static_cast<size_t>(stored_dim);
  if (stored_dim != static_cast<uint32_t>(dim) ||
      num_entries > contents.size() / entry_size ||
      contents.size() != header_size + num_entries * entry_size + 8) {
    return entries;
  }
  std::memcpy(&stored_hash, contents.data() + contents.size() - 8, 8);
  if (HashBytes(contents.data(), contents.size() - 8) != stored_hash) {
    return entries;
  }
  const char* data = contents.data() + header_size;
  for (uint64_t i = 0; i < num_entries; ++i, data += entry_size) {
    uint64_t key;
    std::memcpy(&key, data, 8);
    Eigen::RowVectorXf row(dim);
    std::memcpy(row.data(), data + 8, 4 * static_cast<size_t>(dim));
    entries[key] = std::move(row);
  }
  return entries;
}

void WriteKeyedRowFile(
    const std::string& path,
    const char (&magic)[8],
    const std::string& header,
    int dim,
    const std::vector<std::pair<uint64_t, const float*>>& rows,
    const std::string& what) {
  std::string out(magic, 8);
  out += header;
  const uint32_t stored_dim = static_cast<uint32_t>(dim);
  const uint64_t num_entries = rows.size();
  out.append(reinterpret_cast<const char*>(&stored_dim), 4);
  out.append(reinterpret_cast<const char*>(&num_entries), 8);
  for (const auto& [key, data] : rows) {
    out.append(reinterpret_cast<const char*>(&key), 8);
    out.append(reinterpret_cast<const char*>(data),
               4 * static_cast<size_t>(dim));
  }
  const uint64_t hash = HashBytes(out.data(), out.size());
  out.append(reinterpret_cast<const char*>(&hash), 8);
  try {
    WriteFileAtomically(path, out);
  } catch (const Error& error) {
    LOG(WARNING) << what << " not written: " << error.what();
  }
}

}  // namespace colmap_gcn
