#pragma once

#include <string>

#include "evaluation/bundler.h"

namespace colmap_gcn {
namespace test {

// Writes a Bundler v0.3 file (full double precision), as the 1DSfM
// dataset's references are written, for ReadBundlerFile to read.
void WriteBundlerFile(const std::string& path, const BundlerFile& bundle);

}  // namespace test
}  // namespace colmap_gcn
