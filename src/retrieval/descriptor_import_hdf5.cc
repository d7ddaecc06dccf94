// Reading hloc's global-descriptors HDF5 files, defensively: the files come
// from other programs, and libhdf5 1.10 trusts more of a file than it should.
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
namespace {

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

}  // namespace colmap_gcn
