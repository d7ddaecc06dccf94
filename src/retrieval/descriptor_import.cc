#include "retrieval/descriptor_import.h"

#include <fcntl.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

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

// Closes an HDF5 handle on scope exit.
class Hdf5Handle {
 public:
  Hdf5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Hdf5Handle() {
    if (id_ >= 0) close_(id_);
  }
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  hid_t Id() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// libhdf5 1.10's metadata accumulator, which its stock file drivers turn
// on, serves a read at the undefined address (all bits set, as a corrupt
// group's local heap address can be) by copying from a null pointer. The public
// API cannot show such an address before HDF5 follows it, so files are opened
// through this minimal read-only POSIX driver instead: it leaves the
// accumulator off and refuses reads outside the addressable range (HDF5 turns
// that into an error), and otherwise reads like the default sec2 driver, zeros
// past the end included.
struct CheckedHdf5File {
  H5FD_t base;  // First member: HDF5 passes &base to the callbacks.
  int fd;
  dev_t device;
  ino_t inode;
  haddr_t eoa;
  haddr_t eof;
};

// Largest offset pread takes, as in the sec2 driver.
constexpr haddr_t kMaxHdf5FileAddress = (haddr_t(1) << 63) - 1;

CheckedHdf5File* AsChecked(H5FD_t* file) {
  return reinterpret_cast<CheckedHdf5File*>(file);
}
const CheckedHdf5File* AsChecked(const H5FD_t* file) {
  return reinterpret_cast<const CheckedHdf5File*>(file);
}

H5FD_t* CheckedHdf5Open(const char* name, unsigned flags, hid_t, haddr_t) {
  if ((flags & (H5F_ACC_RDWR | H5F_ACC_TRUNC | H5F_ACC_CREAT)) != 0) {
    return nullptr;
  }
  const int fd = open(name, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return nullptr;
  struct stat status;
  CheckedHdf5File* file = nullptr;
  if (fstat(fd, &status) != 0 ||
      (file = new (std::nothrow) CheckedHdf5File()) == nullptr) {
    close(fd);
    return nullptr;
  }
  file->fd = fd;
  file->device = status.st_dev;
  file->inode = status.st_ino;
  file->eof = static_cast<haddr_t>(status.st_size);
  return &file->base;
}

herr_t CheckedHdf5Close(H5FD_t* base) {
  CheckedHdf5File* file = AsChecked(base);
  const int result = close(file->fd);
  delete file;
  return result == 0 ? 0 : -1;
}

int CheckedHdf5Compare(const H5FD_t* base1, const H5FD_t* base2) {
  const CheckedHdf5File* file1 = AsChecked(base1);
  const CheckedHdf5File* file2 = AsChecked(base2);
  if (file1->device != file2->device) {
    return file1->device < file2->device ? -1 : 1;
  }
  if (file1->inode != file2->inode) return file1->inode < file2->inode ? -1 : 1;
  return 0;
}

herr_t CheckedHdf5Query(const H5FD_t*, unsigned long* flags) {
  if (flags != nullptr) *flags = 0;
  return 0;
}

haddr_t CheckedHdf5GetEoa(const H5FD_t* file, H5FD_mem_t) {
  return AsChecked(file)->eoa;
}

herr_t CheckedHdf5SetEoa(H5FD_t* file, H5FD_mem_t, haddr_t address) {
  if (address > kMaxHdf5FileAddress) return -1;
  AsChecked(file)->eoa = address;
  return 0;
}

haddr_t CheckedHdf5GetEof(const H5FD_t* file, H5FD_mem_t) {
  return AsChecked(file)->eof;
}

herr_t CheckedHdf5Read(H5FD_t* base,
                       H5FD_mem_t,
                       hid_t,
                       haddr_t address,
                       size_t size,
                       void* buffer) {
  const CheckedHdf5File* file = AsChecked(base);
  if (address > kMaxHdf5FileAddress || size > kMaxHdf5FileAddress - address) {
    return -1;
  }
  unsigned char* out = static_cast<unsigned char*>(buffer);
  while (size > 0 && address < file->eof) {
    const size_t wanted =
        static_cast<size_t>(std::min<haddr_t>(size, file->eof - address));
    const ssize_t got =
        pread(file->fd, out, wanted, static_cast<off_t>(address));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return -1;
    if (got == 0) break;
    out += got;
    address += static_cast<haddr_t>(got);
    size -= static_cast<size_t>(got);
  }
  std::memset(out, 0, size);
  return 0;
}

herr_t CheckedHdf5Write(
    H5FD_t*, H5FD_mem_t, hid_t, haddr_t, size_t, const void*) {
  return -1;
}

// Registered once per HDF5 library lifetime.
hid_t CheckedHdf5Driver() {
  static hid_t driver = -1;
  if (driver >= 0 && H5Iis_valid(driver) > 0) return driver;
  static H5FD_class_t driver_class;
  driver_class.name = "colmap_gcn_checked";
  driver_class.maxaddr = kMaxHdf5FileAddress;
  driver_class.fc_degree = H5F_CLOSE_WEAK;
  driver_class.open = CheckedHdf5Open;
  driver_class.close = CheckedHdf5Close;
  driver_class.cmp = CheckedHdf5Compare;
  driver_class.query = CheckedHdf5Query;
  driver_class.get_eoa = CheckedHdf5GetEoa;
  driver_class.set_eoa = CheckedHdf5SetEoa;
  driver_class.get_eof = CheckedHdf5GetEof;
  driver_class.read = CheckedHdf5Read;
  driver_class.write = CheckedHdf5Write;
  const H5FD_mem_t free_list_map[H5FD_MEM_NTYPES] = H5FD_FLMAP_DICHOTOMY;
  std::copy(
      free_list_map, free_list_map + H5FD_MEM_NTYPES, driver_class.fl_map);
  driver = H5FDregister(&driver_class);
  return driver;
}

const char kHdf5DatasetName[] = "global_descriptor";
// Global descriptors have at most a few thousand dimensions (NetVLAD 4096).
constexpr hsize_t kMaxHdf5DescriptorDim = 1 << 20;

// State of the group walk of ListDescriptorPaths.
struct Hdf5GroupWalk {
  std::string prefix;  // Path of the group being listed plus '/', or "".
  std::vector<std::string> groups;  // Groups still to list.
  std::set<haddr_t> seen;           // Addresses of groups queued or listed.
  std::vector<std::string> dataset_paths;
};

herr_t CollectLink(hid_t group,
                   const char* name,
                   const H5L_info_t* link,
                   void* data) {
  Hdf5GroupWalk* walk = static_cast<Hdf5GroupWalk*>(data);
  const std::string path = walk->prefix + name;
  const std::string suffix = std::string("/") + kHdf5DatasetName;
  if (path.size() > suffix.size() &&
      path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0) {
    walk->dataset_paths.push_back(path);
  }
  if (link->type != H5L_TYPE_HARD) return 0;
  H5O_info_t info;
  if (H5Oget_info_by_name2(group, name, &info, H5O_INFO_BASIC, H5P_DEFAULT) <
      0) {
    return -1;
  }
  if (info.type == H5O_TYPE_GROUP && walk->seen.insert(info.addr).second) {
    walk->groups.push_back(path);
  }
  return 0;
}

// The paths of all links named kHdf5DatasetName below the root, like
// H5Lvisit but listing each group object once, without recursion: H5Lvisit
// only remembers groups whose header counts more than one link, so a corrupt
// file whose group links back to itself or an ancestor made it recurse until
// the stack overflowed.
std::vector<std::string> ListDescriptorPaths(hid_t file,
                                             const std::string& path) {
  Hdf5GroupWalk walk;
  walk.groups.push_back("/");
  std::set<haddr_t> listed;
  while (!walk.groups.empty()) {
    const std::string group_path = walk.groups.back();
    walk.groups.pop_back();
    const Hdf5Handle group(H5Gopen2(file, group_path.c_str(), H5P_DEFAULT),
                           H5Gclose);
    H5O_info_t info;
    if (group.Id() < 0 || H5Oget_info2(group.Id(), &info, H5O_INFO_BASIC) < 0) {
      ThrowError("cannot list the groups of HDF5 file ", path);
    }
    walk.seen.insert(info.addr);
    if (!listed.insert(info.addr).second) continue;
    walk.prefix = group_path == "/" ? "" : group_path + "/";
    if (H5Literate(group.Id(),
                   H5_INDEX_NAME,
                   H5_ITER_INC,
                   nullptr,
                   CollectLink,
                   &walk) < 0) {
      ThrowError("cannot list the groups of HDF5 file ", path);
    }
  }
  return walk.dataset_paths;
}

// libhdf5 1.10 trusts the storage description of a dataset: a compact
// dataset smaller than its shape makes H5Dread copy from a null pointer, a
// huge chunk makes it allocate and clear the chunk. Checked before reading.
void CheckHdf5Layout(hid_t dataset,
                     hsize_t data_bytes,
                     const std::string& path,
                     const std::string& dataset_path) {
  const Hdf5Handle properties(H5Dget_create_plist(dataset), H5Pclose);
  const H5D_layout_t layout = H5Pget_layout(properties.Id());
  if (layout == H5D_COMPACT) {
    if (H5Dget_storage_size(dataset) != data_bytes) {
      ThrowError(path,
                 ": ",
                 dataset_path,
                 " is corrupt (compact storage of ",
                 H5Dget_storage_size(dataset),
                 " bytes for ",
                 data_bytes,
                 ")");
    }
  } else if (layout == H5D_CHUNKED) {
    hsize_t chunk[H5S_MAX_RANK];
    const int rank = H5Pget_chunk(properties.Id(), H5S_MAX_RANK, chunk);
    bool valid = rank >= 1;
    hsize_t elements = 1;
    for (int i = 0; valid && i < rank; ++i) {
      // Bounded factor by factor, so the product cannot overflow.
      valid = chunk[i] > 0 && chunk[i] <= kMaxHdf5DescriptorDim &&
              elements * chunk[i] <= kMaxHdf5DescriptorDim;
      elements *= chunk[i];
    }
    if (!valid) {
      ThrowError(path, ": ", dataset_path, " has corrupt or huge chunks");
    }
  } else if (layout != H5D_CONTIGUOUS) {
    ThrowError(path, ": ", dataset_path, " has an unsupported storage layout");
  }
}

}  // namespace

ImportedDescriptors ReadHdf5GlobalDescriptors(const std::string& path) {
  if (!ExistsFile(path)) {
    ThrowError("descriptor file ", path, " does not exist");
  }
  // Errors are reported through our exceptions, not HDF5's stderr dump.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const Hdf5Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (access.Id() < 0 ||
      H5Pset_driver(access.Id(), CheckedHdf5Driver(), nullptr) < 0) {
    ThrowError("cannot set up libhdf5 to read ", path);
  }
  const Hdf5Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, access.Id()),
                        H5Fclose);
  if (file.Id() < 0) {
    ThrowError(path, " is not a readable HDF5 file");
  }
  std::vector<std::string> dataset_paths = ListDescriptorPaths(file.Id(), path);
  std::sort(dataset_paths.begin(), dataset_paths.end());
  if (dataset_paths.empty()) {
    ThrowError("HDF5 file ",
               path,
               " has no <image name>/",
               kHdf5DatasetName,
               " datasets");
  }
  ImportedDescriptors imported;
  std::vector<std::vector<float>> rows;
  for (const std::string& dataset_path : dataset_paths) {
    const std::string name =
        dataset_path.substr(0, dataset_path.size() - sizeof(kHdf5DatasetName));
    const Hdf5Handle dataset(
        H5Dopen2(file.Id(), dataset_path.c_str(), H5P_DEFAULT), H5Dclose);
    if (dataset.Id() < 0) {
      ThrowError(path, ": ", dataset_path, " is not a dataset");
    }
    const Hdf5Handle type(H5Dget_type(dataset.Id()), H5Tclose);
    if (H5Tget_class(type.Id()) != H5T_FLOAT) {
      ThrowError(path, ": ", dataset_path, " is not floating point");
    }
    // HDF5 allocates and clears a conversion buffer of the file's element
    // size, which a corrupt type can make gigabytes per value.
    const size_t type_size = H5Tget_size(type.Id());
    if (type_size != 2 && type_size != 4 && type_size != 8) {
      ThrowError(path,
                 ": ",
                 dataset_path,
                 " has ",
                 type_size,
                 "-byte floats (float16/32/64 only)");
    }
    const Hdf5Handle space(H5Dget_space(dataset.Id()), H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(space.Id());
    hsize_t dims[2] = {0, 0};
    if (rank < 1 || rank > 2 ||
        H5Sget_simple_extent_dims(space.Id(), dims, nullptr) < 0 ||
        (rank == 2 && dims[0] != 1)) {
      ThrowError(path, ": ", dataset_path, " must have shape (D,) or (1, D)");
    }
    const hsize_t dim = rank == 1 ? dims[0] : dims[1];
    // The shape comes from the file: bound it before allocating a row.
    if (dim > kMaxHdf5DescriptorDim) {
      ThrowError(path,
                 ": ",
                 dataset_path,
                 " has ",
                 dim,
                 " dimensions, more than ",
                 kMaxHdf5DescriptorDim);
    }
    CheckHdf5Layout(dataset.Id(), dim * type_size, path, dataset_path);
    std::vector<float> row(dim);
    // HDF5 converts float16 (and float64) to native float on read.
    if (dim == 0 || H5Dread(dataset.Id(),
                            H5T_NATIVE_FLOAT,
                            H5S_ALL,
                            H5S_ALL,
                            H5P_DEFAULT,
                            row.data()) < 0) {
      ThrowError(path, ": cannot read ", dataset_path);
    }
    if (!rows.empty() && row.size() != rows[0].size()) {
      ThrowError(path,
                 ": ",
                 dataset_path,
                 " has ",
                 row.size(),
                 " dimensions, ",
                 imported.names[0],
                 " has ",
                 rows[0].size());
    }
    imported.names.push_back(name);
    rows.push_back(std::move(row));
  }
  imported.vectors.resize(rows.size(), rows[0].size());
  for (size_t i = 0; i < rows.size(); ++i) {
    imported.vectors.row(i) =
        Eigen::Map<const Eigen::RowVectorXf>(rows[i].data(), rows[i].size());
  }
  return imported;
}

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
