// Reading global descriptors from a .npy matrix and its names file.
#include "retrieval/descriptor_import.h"

#include <algorithm>
#include <cstring>
#include <sstream>

#include "util/error.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {

namespace {

std::vector<std::string> ReadNameList(const std::string& path) {
  std::vector<std::string> names;
  std::istringstream stream(ReadTextFile(path));
  std::string line;
  while (std::getline(stream, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    names.push_back(line);
  }
  return names;
}

std::string NpyNamesPath(const std::string& path) {
  if (ExistsFile(path + ".txt")) {
    return path + ".txt";
  }
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) {
    const std::string replaced = path.substr(0, dot) + ".txt";
    if (ExistsFile(replaced)) {
      return replaced;
    }
  }
  ThrowError("no image names for ",
             path,
             ": expected ",
             path,
             ".txt with one name per line");
}

// The value of 'key' in the .npy header dict, up to the next ',' at nesting
// level 0 (shape tuples contain commas).
std::string NpyHeaderValue(const std::string& header,
                           const std::string& key,
                           const std::string& path) {
  const size_t at = header.find("'" + key + "'");
  if (at == std::string::npos) {
    ThrowError(path, ": .npy header has no '", key, "'");
  }
  size_t begin = header.find(':', at);
  if (begin == std::string::npos) {
    ThrowError(path, ": malformed .npy header");
  }
  ++begin;
  int depth = 0;
  size_t end = begin;
  for (; end < header.size(); ++end) {
    const char c = header[end];
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if ((c == ',' && depth == 0) || c == '}') break;
  }
  return StringTrim(header.substr(begin, end - begin));
}

// One entry of the shape tuple: a decimal count (no sign, no overflow).
size_t ParseNpyDimension(const std::string& field,
                         const std::string& shape,
                         const std::string& path) {
  const std::string digits = StringTrim(field);
  if (digits.empty() || digits.size() > 18 ||
      digits.find_first_not_of("0123456789") != std::string::npos) {
    ThrowError(path, ": expected a 2-D array N x D, shape is ", shape);
  }
  return std::stoull(digits);
}

}  // namespace

ImportedDescriptors ReadNpyGlobalDescriptors(const std::string& path) {
  if (!ExistsFile(path)) {
    ThrowError("descriptor file ", path, " does not exist");
  }
  const std::string contents = ReadTextFile(path);
  if (contents.size() < 10 || contents.compare(0, 6, "\x93NUMPY") != 0) {
    ThrowError(path, " is not a .npy file");
  }
  const int major = static_cast<unsigned char>(contents[6]);
  size_t header_length;
  size_t header_start;
  if (major == 1) {
    header_length = static_cast<unsigned char>(contents[8]) |
                    (static_cast<unsigned char>(contents[9]) << 8);
    header_start = 10;
  } else if (major == 2 || major == 3) {
    if (contents.size() < 12) ThrowError(path, " is truncated");
    uint32_t length;
    std::memcpy(&length, contents.data() + 8, 4);
    header_length = length;
    header_start = 12;
  } else {
    ThrowError(path, ": unsupported .npy version ", major);
  }
  if (contents.size() < header_start + header_length) {
    ThrowError(path, " is truncated");
  }
  const std::string header = contents.substr(header_start, header_length);
  const std::string descr = NpyHeaderValue(header, "descr", path);
  const std::string fortran = NpyHeaderValue(header, "fortran_order", path);
  const std::string shape = NpyHeaderValue(header, "shape", path);
  if (fortran != "False") {
    ThrowError(path, ": Fortran-order .npy is not supported; save C order");
  }
  int element_size;
  if (descr == "'<f2'") {
    element_size = 2;
  } else if (descr == "'<f4'") {
    element_size = 4;
  } else if (descr == "'<f8'") {
    element_size = 8;
  } else {
    ThrowError(path,
               ": unsupported dtype ",
               descr,
               " (little-endian float16/32/64 only)");
  }
  // shape "(N, D)".
  const std::vector<std::string> parts =
      shape.size() < 2 ? std::vector<std::string>()
                       : StringSplit(shape.substr(1, shape.size() - 2), ",");
  if (shape.size() < 2 || shape.front() != '(' || shape.back() != ')' ||
      parts.size() != 2 || StringTrim(parts[1]).empty()) {
    ThrowError(path, ": expected a 2-D array N x D, shape is ", shape);
  }
  const size_t num_rows = ParseNpyDimension(parts[0], shape, path);
  const size_t dim = ParseNpyDimension(parts[1], shape, path);
  if (dim == 0) {
    ThrowError(path, ": descriptors have no dimensions, shape is ", shape);
  }
  // Compared by division so that a huge shape cannot overflow the product.
  const size_t data_start = header_start + header_length;
  const size_t data_size = contents.size() - data_start;
  const size_t num_elements = data_size / element_size;
  if (data_size % element_size != 0 || num_elements % dim != 0 ||
      num_elements / dim != num_rows) {
    ThrowError(path, ": data size does not match shape ", shape);
  }
  ImportedDescriptors imported;
  imported.names = ReadNameList(NpyNamesPath(path));
  if (imported.names.size() != num_rows) {
    ThrowError(path,
               " has ",
               num_rows,
               " rows but its names list has ",
               imported.names.size(),
               " names");
  }
  imported.vectors.resize(num_rows, dim);
  const char* data = contents.data() + data_start;
  for (size_t i = 0; i < num_rows * dim; ++i) {
    float value;
    if (element_size == 2) {
      uint16_t half;
      std::memcpy(&half, data + 2 * i, 2);
      value = HalfToFloat(half);
    } else if (element_size == 4) {
      std::memcpy(&value, data + 4 * i, 4);
    } else {
      double wide;
      std::memcpy(&wide, data + 8 * i, 8);
      value = static_cast<float>(wide);
    }
    imported.vectors.data()[i] = value;
  }
  return imported;
}

}  // namespace colmap_gcn
