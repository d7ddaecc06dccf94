#include "retrieval/descriptor_import.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <map>
#include <new>
#include <set>
#include <sstream>

#include "util/error.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {

float HalfToFloat(uint16_t half) {
  const uint32_t sign = static_cast<uint32_t>(half & 0x8000) << 16;
  const int exponent = (half >> 10) & 0x1f;
  const uint32_t mantissa = half & 0x3ff;
  float value;
  if (exponent == 0) {
    value = std::ldexp(static_cast<float>(mantissa), -24);  // subnormal
  } else if (exponent == 31) {
    value = mantissa == 0 ? INFINITY : NAN;
  } else {
    value = std::ldexp(static_cast<float>(mantissa | 0x400), exponent - 25);
  }
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof(bits));
  bits |= sign;
  std::memcpy(&value, &bits, sizeof(bits));
  return value;
}

namespace {

// Lists at most a few names, then the count.
std::string NameList(const std::vector<std::string>& names) {
  const size_t kMaxListed = 10;
  std::vector<std::string> listed(
      names.begin(), names.begin() + std::min(names.size(), kMaxListed));
  std::string list = StringJoin(listed, ", ");
  if (names.size() > kMaxListed) {
    list += ", ... (" + std::to_string(names.size()) + " in all)";
  }
  return list;
}

}  // namespace

ImportedDescriptors ReadTextGlobalDescriptors(const std::string& path) {
  if (!ExistsFile(path)) {
    ThrowError("descriptor file ", path, " does not exist");
  }
  std::istringstream stream(ReadTextFile(path));
  std::string line;
  std::vector<std::vector<float>> rows;
  ImportedDescriptors imported;
  int line_number = 0;
  while (std::getline(stream, line)) {
    ++line_number;
    line = StringTrim(line);
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name;
    fields >> name;
    std::vector<float> row;
    std::string token;
    while (fields >> token) {
      try {
        size_t used = 0;
        row.push_back(std::stof(token, &used));
        if (used != token.size()) throw std::invalid_argument(token);
      } catch (const std::exception&) {
        ThrowError(path, ":", line_number, ": not a number: ", token);
      }
    }
    if (row.empty() || (!rows.empty() && row.size() != rows[0].size())) {
      ThrowError(path,
                 ":",
                 line_number,
                 ": expected \"name v1 ... vD\" with the same D on every line");
    }
    imported.names.push_back(name);
    rows.push_back(std::move(row));
  }
  if (rows.empty()) {
    ThrowError(path, " has no descriptors");
  }
  imported.vectors.resize(rows.size(), rows[0].size());
  for (size_t i = 0; i < rows.size(); ++i) {
    imported.vectors.row(i) =
        Eigen::Map<const Eigen::RowVectorXf>(rows[i].data(), rows[i].size());
  }
  return imported;
}

ImportedDescriptors ReadGlobalDescriptors(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const std::string extension =
      dot == std::string::npos ? "" : path.substr(dot + 1);
  if (extension == "h5" || extension == "hdf5") {
    return ReadHdf5GlobalDescriptors(path);
  }
  if (extension == "npy") {
    return ReadNpyGlobalDescriptors(path);
  }
  if (extension == "txt") {
    return ReadTextGlobalDescriptors(path);
  }
  ThrowError("unknown descriptor file type ",
             path,
             " (expected .h5/.hdf5, .npy or .txt)");
}

EmbeddingMatrix MatchDescriptorsToImages(
    const ImportedDescriptors& imported,
    const std::vector<DatabaseImage>& images,
    std::vector<image_t>* image_ids) {
  THROW_CHECK(imported.names.size() ==
              static_cast<size_t>(imported.vectors.rows()));
  std::map<std::string, int> rows_by_name;
  std::vector<std::string> duplicates;
  for (size_t i = 0; i < imported.names.size(); ++i) {
    if (!rows_by_name.emplace(imported.names[i], static_cast<int>(i)).second) {
      duplicates.push_back(imported.names[i]);
    }
  }
  if (!duplicates.empty()) {
    ThrowError("duplicate image names in imported descriptors: ",
               NameList(duplicates));
  }
  std::vector<DatabaseImage> sorted = images;
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    return a.image_id < b.image_id;
  });
  std::vector<std::string> missing;
  std::set<std::string> database_names;
  for (const DatabaseImage& image : sorted) {
    database_names.insert(image.name);
    if (rows_by_name.count(image.name) == 0) missing.push_back(image.name);
  }
  std::vector<std::string> unknown;
  for (const std::string& name : imported.names) {
    if (database_names.count(name) == 0) unknown.push_back(name);
  }
  if (!missing.empty() || !unknown.empty()) {
    std::string message = "imported descriptors do not match the database:";
    if (!missing.empty()) {
      message += " no descriptor for database image(s) " + NameList(missing);
      if (!unknown.empty()) message += ";";
    }
    if (!unknown.empty()) {
      message += " not in the database: " + NameList(unknown);
    }
    ThrowError(message);
  }
  EmbeddingMatrix embeddings(sorted.size(), imported.vectors.cols());
  image_ids->clear();
  for (size_t i = 0; i < sorted.size(); ++i) {
    image_ids->push_back(sorted[i].image_id);
    embeddings.row(i) = imported.vectors.row(rows_by_name.at(sorted[i].name));
    if (!embeddings.row(i).allFinite()) {
      ThrowError("imported descriptor of ", sorted[i].name, " is not finite");
    }
    const float norm = embeddings.row(i).norm();
    if (norm > 0) embeddings.row(i) /= norm;
  }
  return embeddings;
}

}  // namespace colmap_gcn
