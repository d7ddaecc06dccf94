#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace colmap_gcn {

// The benchmark's result files and caches. nlohmann::json keeps object keys
// sorted, so the files are deterministic.
using Json = nlohmann::json;

// Reads and parses a file; throws Error naming the file (one line).
Json ReadJsonFile(const std::string& path);

// Writes the value with two-space indentation and a final newline,
// atomically (see WriteFileAtomically). Non-finite numbers are written as
// null; bytes that are not UTF-8 become U+FFFD rather than failing.
void WriteJsonFile(const std::string& path, const Json& value);

}  // namespace colmap_gcn
