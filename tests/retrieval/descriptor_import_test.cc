#include "retrieval/descriptor_import.h"

#include <hdf5.h>

#include <gtest/gtest.h>

#include <cstring>

#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

// hloc-style file: /<name>/global_descriptor, names with '/' nested.
void WriteHdf5(const std::string& path, bool half) {
  const hid_t file =
      H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(lcpl, 1);
  // IEEE binary16 as h5py/numpy write it.
  const hid_t f16 = H5Tcopy(H5T_IEEE_F32LE);
  H5Tset_fields(f16, 15, 10, 5, 0, 10);
  H5Tset_size(f16, 2);
  H5Tset_ebias(f16, 15);
  H5Tset_precision(f16, 16);
  struct Entry {
    const char* name;
    uint16_t half[3];
    float full[3];
  };
  // 1.0 = 0x3c00, 2.0 = 0x4000, -0.5 = 0xb800, 0.25 = 0x3400, 0 = 0.
  const Entry entries[] = {
      {"a.jpg", {0x3c00, 0x4000, 0xb800}, {1.f, 2.f, -0.5f}},
      {"sub/b.jpg", {0x0000, 0x3400, 0x3c00}, {0.f, 0.25f, 1.f}},
      {"sub/deeper/c.jpg", {0x4000, 0x4000, 0x0000}, {2.f, 2.f, 0.f}},
  };
  for (const Entry& entry : entries) {
    const hsize_t dims[1] = {3};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const std::string dataset_path =
        std::string(entry.name) + "/global_descriptor";
    const hid_t dataset = H5Dcreate2(file,
                                     dataset_path.c_str(),
                                     half ? f16 : H5T_IEEE_F32LE,
                                     space,
                                     lcpl,
                                     H5P_DEFAULT,
                                     H5P_DEFAULT);
    ASSERT_GE(dataset, 0);
    if (half) {
      H5Dwrite(dataset, f16, H5S_ALL, H5S_ALL, H5P_DEFAULT, entry.half);
    } else {
      H5Dwrite(
          dataset, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, entry.full);
    }
    H5Dclose(dataset);
    H5Sclose(space);
  }
  // An unrelated dataset next to a descriptor (hloc stores image_size).
  {
    const hsize_t dims[1] = {2};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const hid_t dataset = H5Dcreate2(file,
                                     "a.jpg/image_size",
                                     H5T_NATIVE_INT,
                                     space,
                                     lcpl,
                                     H5P_DEFAULT,
                                     H5P_DEFAULT);
    const int size[2] = {640, 480};
    H5Dwrite(dataset, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, size);
    H5Dclose(dataset);
    H5Sclose(space);
  }
  H5Tclose(f16);
  H5Pclose(lcpl);
  H5Fclose(file);
}

std::vector<DatabaseImage> Images(const std::vector<std::string>& names) {
  std::vector<DatabaseImage> images;
  for (size_t i = 0; i < names.size(); ++i) {
    DatabaseImage image;
    image.image_id = static_cast<image_t>(10 - i);  // ids not in name order
    image.name = names[i];
    image.camera_id = 1;
    images.push_back(image);
  }
  return images;
}

void ExpectThreeVectors(const ImportedDescriptors& imported) {
  ASSERT_EQ(
      imported.names,
      (std::vector<std::string>{"a.jpg", "sub/b.jpg", "sub/deeper/c.jpg"}));
  ASSERT_EQ(imported.vectors.rows(), 3);
  ASSERT_EQ(imported.vectors.cols(), 3);
  EXPECT_EQ(imported.vectors(0, 0), 1.f);
  EXPECT_EQ(imported.vectors(0, 1), 2.f);
  EXPECT_EQ(imported.vectors(0, 2), -0.5f);
  EXPECT_EQ(imported.vectors(1, 1), 0.25f);
  EXPECT_EQ(imported.vectors(2, 0), 2.f);
}

TEST(HalfToFloat, DecodesSpecialValues) {
  EXPECT_EQ(HalfToFloat(0x3c00), 1.f);
  EXPECT_EQ(HalfToFloat(0xc000), -2.f);
  EXPECT_EQ(HalfToFloat(0x7bff), 65504.f);
  EXPECT_EQ(HalfToFloat(0x0001), std::ldexp(1.f, -24));
  EXPECT_TRUE(std::isinf(HalfToFloat(0x7c00)));
  EXPECT_TRUE(std::isnan(HalfToFloat(0x7e00)));
  EXPECT_TRUE(std::signbit(HalfToFloat(0x8000)));
}

TEST(Hdf5Import, ReadsFloat16AndFloat32WithNestedNames) {
  const TemporaryDirectory dir;
  for (const bool half : {true, false}) {
    const std::string path = JoinPaths(dir.Path(), half ? "h.h5" : "f.h5");
    WriteHdf5(path, half);
    ExpectThreeVectors(ReadGlobalDescriptors(path));
  }
}

TEST(Hdf5Import, MatchesByNameAndNormalises) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "g.h5");
  WriteHdf5(path, true);
  std::vector<image_t> image_ids;
  const EmbeddingMatrix embeddings = MatchDescriptorsToImages(
      ReadGlobalDescriptors(path),
      Images({"sub/deeper/c.jpg", "a.jpg", "sub/b.jpg"}),
      &image_ids);
  // Ascending ids: 8 (sub/b.jpg), 9 (a.jpg), 10 (sub/deeper/c.jpg).
  EXPECT_EQ(image_ids, (std::vector<image_t>{8, 9, 10}));
  EXPECT_NEAR(embeddings(1, 1), 2.f / std::sqrt(5.25f), 1e-6);
  EXPECT_NEAR(embeddings(2, 0), std::sqrt(0.5f), 1e-6);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(embeddings.row(i).norm(), 1, 1e-6);
}

TEST(Hdf5Import, MissingAndUnknownNamesAreErrorsNamingThem) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "g.h5");
  WriteHdf5(path, false);
  std::vector<image_t> image_ids;
  try {
    MatchDescriptorsToImages(ReadGlobalDescriptors(path),
                             Images({"a.jpg", "sub/b.jpg", "d.jpg"}),
                             &image_ids);
    FAIL() << "no error";
  } catch (const Error& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("d.jpg"), std::string::npos) << what;
    EXPECT_NE(what.find("sub/deeper/c.jpg"), std::string::npos) << what;
    EXPECT_EQ(what.find("a.jpg"), std::string::npos) << what;
  }
  // Similar-looking names are not guessed.
  EXPECT_THROW(MatchDescriptorsToImages(
                   ReadGlobalDescriptors(path),
                   Images({"A.jpg", "sub/b.jpg", "sub/deeper/c.jpg"}),
                   &image_ids),
               Error);
  WriteFileAtomically(JoinPaths(dir.Path(), "x.h5"), "not hdf5");
  EXPECT_THROW(ReadGlobalDescriptors(JoinPaths(dir.Path(), "x.h5")), Error);
  EXPECT_THROW(ReadGlobalDescriptors(JoinPaths(dir.Path(), "none.h5")), Error);
}

std::string NpyFile(const std::string& descr,
                    const std::string& shape,
                    const void* data,
                    size_t size) {
  std::string header = "{'descr': '" + descr +
                       "', 'fortran_order': False, 'shape': " + shape + ", }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += static_cast<char>(header.size() & 0xff);
  out += static_cast<char>(header.size() >> 8);
  out += header;
  out.append(static_cast<const char*>(data), size);
  return out;
}

TEST(NpyImport, RoundTripsFloat16_32_64) {
  const TemporaryDirectory dir;
  const float f32[6] = {1, 2, -0.5f, 0, 0.25f, 1};
  const double f64[6] = {1, 2, -0.5, 0, 0.25, 1};
  const uint16_t f16[6] = {0x3c00, 0x4000, 0xb800, 0, 0x3400, 0x3c00};
  const struct {
    const char* descr;
    const void* data;
    size_t size;
  } cases[] = {{"<f4", f32, sizeof(f32)},
               {"<f8", f64, sizeof(f64)},
               {"<f2", f16, sizeof(f16)}};
  for (const auto& c : cases) {
    const std::string path =
        JoinPaths(dir.Path(), std::string(c.descr + 1) + ".npy");
    WriteFileAtomically(path, NpyFile(c.descr, "(2, 3)", c.data, c.size));
    WriteFileAtomically(path + ".txt", "x/one.png\ntwo.png\n");
    const ImportedDescriptors imported = ReadGlobalDescriptors(path);
    EXPECT_EQ(imported.names,
              (std::vector<std::string>{"x/one.png", "two.png"}));
    ASSERT_EQ(imported.vectors.rows(), 2);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(imported.vectors.data()[i], f32[i]);
  }
}

TEST(NpyImport, RejectsWhatItCannotRead) {
  const TemporaryDirectory dir;
  const float f32[6] = {1, 2, 3, 4, 5, 6};
  const std::string path = JoinPaths(dir.Path(), "d.npy");
  WriteFileAtomically(path + ".txt", "a\nb\n");
  WriteFileAtomically(path, NpyFile(">f4", "(2, 3)", f32, sizeof(f32)));
  EXPECT_THROW(ReadGlobalDescriptors(path), Error);
  WriteFileAtomically(path, NpyFile("<f4", "(6,)", f32, sizeof(f32)));
  EXPECT_THROW(ReadGlobalDescriptors(path), Error);
  WriteFileAtomically(path, NpyFile("<f4", "(2, 3)", f32, sizeof(f32) - 4));
  EXPECT_THROW(ReadGlobalDescriptors(path), Error);
  WriteFileAtomically(path, NpyFile("<f4", "(3, 2)", f32, sizeof(f32)));
  EXPECT_THROW(ReadGlobalDescriptors(path), Error);  // 3 rows, 2 names
  WriteFileAtomically(path, NpyFile("<f4", "(2, 3)", f32, sizeof(f32)));
  EXPECT_EQ(ReadGlobalDescriptors(path).vectors.rows(), 2);
  const std::string no_names = JoinPaths(dir.Path(), "e.npy");
  WriteFileAtomically(no_names, NpyFile("<f4", "(2, 3)", f32, sizeof(f32)));
  EXPECT_THROW(ReadGlobalDescriptors(no_names), Error);
}

// Shapes the fuzzer found: a non-numeric dimension (std::stoull threw
// std::invalid_argument) and one whose N * D * 8 overflows to the data size
// (2^61 + 1 rows of 1 value: the check passed, then 2^61 rows were read).
TEST(NpyImport, CorruptShapesAreErrorsNamingTheFile) {
  const TemporaryDirectory dir;
  const double f64[3] = {1, 2, 3};
  const std::string path = JoinPaths(dir.Path(), "d.npy");
  WriteFileAtomically(path + ".txt", "a\nb\nc\n");
  for (const char* shape : {"(\xbf, 1)",
                            "(-1, 3)",
                            "(3, 1e2)",
                            "(99999999999999999999999, 1)",
                            "(2305843009213693953, 1)",
                            "(3, 0)"}) {
    WriteFileAtomically(path, NpyFile("<f8", shape, f64, sizeof(f64)));
    try {
      ReadGlobalDescriptors(path);
      ADD_FAILURE() << "no error for shape " << shape;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos)
          << error.what();
    }
  }
  WriteFileAtomically(path, NpyFile("<f8", "(3, 1)", f64, sizeof(f64)));
  EXPECT_EQ(ReadGlobalDescriptors(path).vectors.rows(), 3);
}

// A dataspace of 2^40 values (a few bytes in the file, since the data is
// never written) was allocated before reading.
TEST(Hdf5Import, HugeDescriptorShapeIsAnError) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "huge.h5");
  const hid_t file =
      H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t group =
      H5Gcreate2(file, "a.jpg", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[1] = {hsize_t(1) << 40};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t props = H5Pcreate(H5P_DATASET_CREATE);
  const hsize_t chunk[1] = {1024};
  H5Pset_chunk(props, 1, chunk);
  const hid_t dataset = H5Dcreate2(group,
                                   "global_descriptor",
                                   H5T_IEEE_F32LE,
                                   space,
                                   H5P_DEFAULT,
                                   props,
                                   H5P_DEFAULT);
  ASSERT_GE(dataset, 0);
  H5Dclose(dataset);
  H5Pclose(props);
  H5Sclose(space);
  H5Gclose(group);
  H5Fclose(file);
  test::ExpectErrorContaining([&] { ReadGlobalDescriptors(path); },
                              "1099511627776 dimensions");
}

// Found by fuzzing: a float type of 2^30 + 2 bytes (3 values) made H5Dread
// allocate and clear gigabytes; the fuzzer timed out.
TEST(Hdf5Import, HugeFloatTypeIsAnError) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "wide.h5");
  const hid_t file =
      H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t group =
      H5Gcreate2(file, "a.jpg", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t type = H5Tcopy(H5T_IEEE_F64LE);
  ASSERT_GE(H5Tset_size(type, (size_t(1) << 30) + 2), 0);
  const hsize_t dims[1] = {3};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t dataset = H5Dcreate2(group,
                                   "global_descriptor",
                                   type,
                                   space,
                                   H5P_DEFAULT,
                                   H5P_DEFAULT,
                                   H5P_DEFAULT);
  ASSERT_GE(dataset, 0);
  H5Dclose(dataset);
  H5Sclose(space);
  H5Tclose(type);
  H5Gclose(group);
  H5Fclose(file);
  test::ExpectErrorContaining([&] { ReadGlobalDescriptors(path); },
                              "1073741826-byte floats");
}

// Found by fuzzing: a compact dataset whose stored data size says 0 bytes
// for its 3 floats made H5Dread copy from a null pointer (SEGV inside
// libhdf5). The file is a valid compact dataset with that one field zeroed.
TEST(Hdf5Import, CompactDatasetSmallerThanItsShapeIsAnError) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "compact.h5");
  const hid_t file =
      H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t group =
      H5Gcreate2(file, "a.jpg", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[1] = {3};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t props = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_layout(props, H5D_COMPACT);
  const hid_t dataset = H5Dcreate2(group,
                                   "global_descriptor",
                                   H5T_IEEE_F32LE,
                                   space,
                                   H5P_DEFAULT,
                                   props,
                                   H5P_DEFAULT);
  ASSERT_GE(dataset, 0);
  const float values[3] = {1.5f, -2.25f, 3.125f};
  H5Dwrite(dataset, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values);
  H5Dclose(dataset);
  H5Pclose(props);
  H5Sclose(space);
  H5Gclose(group);
  H5Fclose(file);
  EXPECT_EQ(ReadGlobalDescriptors(path).vectors(0, 2), 3.125f);

  // Layout message: version 3, class 0 (compact), u16 size 12, the data.
  std::string bytes = ReadTextFile(path);
  std::string message("\x03\x00\x0c\x00", 4);
  message.append(reinterpret_cast<const char*>(values), sizeof(values));
  const size_t at = bytes.find(message);
  ASSERT_NE(at, std::string::npos);
  bytes[at + 2] = 0;
  WriteFileAtomically(path, bytes);
  test::ExpectErrorContaining([&] { ReadGlobalDescriptors(path); },
                              "compact storage of 0 bytes");
}

// Found by fuzzing: a group whose symbol table gives the undefined address
// (all bits set) for its local heap made libhdf5's metadata accumulator copy
// from a null pointer inside H5Lvisit (SEGV). The file is a valid hloc file
// with that one field of the a.jpg group set.
TEST(Hdf5Import, GroupWithUndefinedHeapAddressIsAnError) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "heap.h5");
  const hid_t file =
      H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t group =
      H5Gcreate2(file, "a.jpg", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[1] = {3};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t dataset = H5Dcreate2(group,
                                   "global_descriptor",
                                   H5T_IEEE_F32LE,
                                   space,
                                   H5P_DEFAULT,
                                   H5P_DEFAULT,
                                   H5P_DEFAULT);
  ASSERT_GE(dataset, 0);
  const float values[3] = {1.5f, -2.25f, 3.125f};
  H5Dwrite(dataset, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values);
  H5Dclose(dataset);
  H5Sclose(space);
  H5Gclose(group);
  H5Fclose(file);
  EXPECT_EQ(ReadGlobalDescriptors(path).vectors(0, 2), 3.125f);

  // Symbol table messages (version 1 object headers): u16 type 0x11, u16
  // size 16, flags and 3 reserved bytes, B-tree address, heap address. The
  // root group's comes first, then that of a.jpg.
  std::string bytes = ReadTextFile(path);
  const std::string message("\x11\x00\x10\x00", 4);
  const size_t root = bytes.find(message);
  ASSERT_NE(root, std::string::npos);
  const size_t at = bytes.find(message, root + 1);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(bytes.find(message, at + 1), std::string::npos);
  for (size_t i = at + 16; i < at + 24; ++i) bytes[i] = '\xff';
  WriteFileAtomically(path, bytes);
  try {
    ReadGlobalDescriptors(path);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()),
              "cannot list the groups of HDF5 file " + path);
  }
}

// Found by fuzzing: a group linked from inside itself whose object header
// counts one link made H5Lvisit, which only remembers groups counting more,
// recurse until the stack overflowed. The file is a valid one with the cycle
// (dir/c.jpg is dir) and that count patched from 2 to 1; each group is
// listed once.
TEST(Hdf5Import, GroupCycleIsListedOnce) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "cycle.h5");
  const hid_t file =
      H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t group =
      H5Gcreate2(file, "dir", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[1] = {3};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t dataset = H5Dcreate2(group,
                                   "global_descriptor",
                                   H5T_IEEE_F32LE,
                                   space,
                                   H5P_DEFAULT,
                                   H5P_DEFAULT,
                                   H5P_DEFAULT);
  ASSERT_GE(dataset, 0);
  const float values[3] = {1.5f, -2.25f, 3.125f};
  H5Dwrite(dataset, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values);
  ASSERT_GE(
      H5Lcreate_hard(file, "dir", group, "c.jpg", H5P_DEFAULT, H5P_DEFAULT), 0);
  H5O_info_t info;
  ASSERT_GE(H5Oget_info2(group, &info, H5O_INFO_BASIC), 0);
  ASSERT_EQ(info.rc, 2u);
  H5Dclose(dataset);
  H5Sclose(space);
  H5Gclose(group);
  H5Fclose(file);
  EXPECT_EQ(ReadGlobalDescriptors(path).names, std::vector<std::string>{"dir"});

  // Version 1 object header: version, reserved, u16 message count, u32 link
  // count.
  std::string bytes = ReadTextFile(path);
  ASSERT_LT(info.addr + 8, bytes.size());
  ASSERT_EQ(bytes.substr(info.addr, 1), "\x01");
  ASSERT_EQ(bytes.substr(info.addr + 4, 4), std::string("\x02\x00\x00\x00", 4));
  bytes[info.addr + 4] = 1;
  WriteFileAtomically(path, bytes);
  const ImportedDescriptors imported = ReadGlobalDescriptors(path);
  EXPECT_EQ(imported.names, std::vector<std::string>{"dir"});
  EXPECT_EQ(imported.vectors(0, 2), 3.125f);
}

TEST(TextImport, ReadsNameAndValues) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "d.txt");
  WriteFileAtomically(path,
                      "# comment\na.jpg 1 2 -0.5\n\nsub/b.jpg 0 0.25 1\n");
  const ImportedDescriptors imported = ReadGlobalDescriptors(path);
  EXPECT_EQ(imported.names, (std::vector<std::string>{"a.jpg", "sub/b.jpg"}));
  EXPECT_EQ(imported.vectors(0, 2), -0.5f);
  WriteFileAtomically(path, "a.jpg 1 2\nb.jpg 1 2 3\n");
  EXPECT_THROW(ReadGlobalDescriptors(path), Error);
  WriteFileAtomically(path, "a.jpg 1 x\n");
  EXPECT_THROW(ReadGlobalDescriptors(path), Error);
  WriteFileAtomically(path, "a.jpg 1 2\na.jpg 1 2\n");
  std::vector<image_t> ids;
  EXPECT_THROW(MatchDescriptorsToImages(
                   ReadGlobalDescriptors(path), Images({"a.jpg"}), &ids),
               Error);
  EXPECT_THROW(ReadGlobalDescriptors(JoinPaths(dir.Path(), "d.csv")), Error);
}

}  // namespace
}  // namespace colmap_gcn
