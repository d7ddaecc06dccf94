// Writes the seed corpus of the fuzz targets (tests/fuzz/corpus/<target>/):
// a few small valid files per reader, made with our own writers (and the
// HDF5 C API for hloc's layout), so that the fuzzers start from inputs that
// reach deep into the parsers. Usage: make_corpus <corpus dir>.

#include <hdf5.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "evaluation/bundler.h"
#include "evaluation/bundler_writer.h"
#include "fuzz_utils.h"
#include "gcn/model_file.h"
#include "scene/camera_models.h"
#include "scene/model_writer.h"
#include "scene/reconstruction.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

namespace fs = std::filesystem;

void Put(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << bytes;
  if (!file.flush()) ThrowError("cannot write ", path.string());
}

std::string Join(const std::vector<std::string>& files) {
  std::string joined;
  for (size_t i = 0; i < files.size(); ++i) {
    if (i > 0) joined += fuzz::kSeparator;
    joined += files[i];
  }
  return joined;
}

void ModelFiles(const fs::path& dir) {
  GcnShape shape;
  shape.input_dim = 3;
  shape.gcn_dims = {4, 2};
  shape.fc_dim = 2;
  GcnModel model = InitializeGcnModel(shape, GcnAggregation::kSymmetric, 1);
  model.embedding.type = "vlad";
  model.embedding.dim = 3;
  model.embedding.blob = "blob";
  model.info.notes = "seed";
  const std::string bytes = SerializeGcnModel(model);
  Put(dir / "tiny.gcnmodel", bytes);
  // Reserved byte 12 odd: the fuzzer fixes up payload size and checksum.
  std::string fixup = bytes;
  fixup[12] = 1;
  Put(dir / "tiny_fixup.gcnmodel", fixup);
  model = InitializeGcnModel(shape, GcnAggregation::kRowNormalized, 2);
  model.embedding.type = "imported:x";
  model.embedding.dim = 3;
  std::string row = SerializeGcnModel(model);
  row[12] = 1;
  Put(dir / "row_normalized_fixup.gcnmodel", row);
}

void PairsFiles(const fs::path& dir) {
  Put(dir / "pairs.txt", "a.jpg b.jpg\nb.jpg c.jpg\n");
  Put(dir / "scores.txt",
      "# comment\na.jpg b.jpg 0.9\r\n\nc/d.png e.png 0.1\n");
}

void Hdf5File(const fs::path& path,
              bool half,
              const std::vector<std::string>& names) {
  fs::create_directories(path.parent_path());
  const hid_t file =
      H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) ThrowError("cannot create ", path.string());
  const hid_t link_props = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(link_props, 1);
  for (size_t i = 0; i < names.size(); ++i) {
    const hsize_t dims[2] = {1, 3};
    const int rank = half ? 2 : 1;
    const hid_t space = H5Screate_simple(rank, half ? dims : dims + 1, nullptr);
    const hid_t type = H5Tcopy(H5T_IEEE_F32LE);
    if (half) {
      // IEEE binary16 as hloc's float16.
      H5Tset_fields(type, 15, 10, 5, 0, 10);
      H5Tset_size(type, 2);
      H5Tset_ebias(type, 15);
      H5Tset_precision(type, 16);
    }
    const std::string dataset_path = names[i] + "/global_descriptor";
    const hid_t dataset = H5Dcreate2(file,
                                     dataset_path.c_str(),
                                     type,
                                     space,
                                     link_props,
                                     H5P_DEFAULT,
                                     H5P_DEFAULT);
    const float values[3] = {1.0f + i, 0.5f, -2.0f};
    H5Dwrite(dataset, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values);
    H5Dclose(dataset);
    H5Tclose(type);
    H5Sclose(space);
  }
  H5Pclose(link_props);
  H5Fclose(file);
}

std::string Npy(int major, const std::string& descr, int rows, int cols) {
  std::string header =
      "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (" +
      std::to_string(rows) + ", " + std::to_string(cols) + "), }";
  const size_t prefix = major == 1 ? 10 : 12;
  while ((prefix + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string bytes = "\x93NUMPY";
  bytes += static_cast<char>(major);
  bytes += '\0';
  const uint32_t length = header.size();
  bytes.append(reinterpret_cast<const char*>(&length), major == 1 ? 2 : 4);
  bytes += header;
  const int element_size = descr == "<f2" ? 2 : descr == "<f4" ? 4 : 8;
  for (int i = 0; i < rows * cols; ++i) {
    const float value = 0.25f * i - 1.0f;
    if (element_size == 2) {
      const uint16_t half = 0x3c00 + i;  // 1.0 and just above
      bytes.append(reinterpret_cast<const char*>(&half), 2);
    } else if (element_size == 4) {
      bytes.append(reinterpret_cast<const char*>(&value), 4);
    } else {
      const double wide = value;
      bytes.append(reinterpret_cast<const char*>(&wide), 8);
    }
  }
  return bytes;
}

Reconstruction SmallModel() {
  Reconstruction model;
  const char* camera_models[2] = {"SIMPLE_RADIAL", "PINHOLE"};
  for (camera_t id = 1; id <= 2; ++id) {
    ModelCamera camera;
    camera.camera_id = id;
    camera.model_id = CameraModelNameToId(camera_models[id - 1]);
    camera.width = 640;
    camera.height = 480;
    camera.params.assign(CameraModelNumParams(camera.model_id), 100.0 * id);
    model.cameras[id] = camera;
  }
  for (image_t id = 1; id <= 3; ++id) {
    ModelImage image;
    image.image_id = id;
    image.camera_id = id == 3 ? 2 : 1;
    image.qvec = Eigen::Vector4d(1, 0.1 * id, 0, 0).normalized();
    image.tvec = Eigen::Vector3d(id, -1, 0.5);
    image.name = "img" + std::to_string(id) + ".jpg";
    for (int j = 0; j < 2; ++j) {
      image.points2D.emplace_back(10.0 * j + id, 20.0 + j);
      image.point3D_ids.push_back(j == 0 ? 1 : kInvalidPoint3DId);
    }
    model.images[id] = image;
  }
  ModelPoint3D point;
  point.xyz = Eigen::Vector3d(0.5, 1.5, 4);
  point.color << 10, 200, 30;
  point.error = 0.7;
  for (image_t id = 1; id <= 3; ++id) point.track.push_back({id, 0});
  model.points3D[1] = point;
  return model;
}

std::string SparseModelFiles(const Reconstruction& model,
                             bool binary,
                             bool with_points) {
  TemporaryDirectory dir("colmap_gcn_corpus");
  if (binary) {
    test::WriteBinaryModel(model, dir.Path());
  } else {
    model.WriteText(dir.Path());
  }
  const std::string extension = binary ? ".bin" : ".txt";
  std::vector<std::string> files = {
      ReadTextFile(JoinPaths(dir.Path(), "cameras" + extension)),
      ReadTextFile(JoinPaths(dir.Path(), "images" + extension))};
  if (with_points) {
    files.push_back(
        ReadTextFile(JoinPaths(dir.Path(), "points3D" + extension)));
  }
  return Join(files);
}

void Generate(const fs::path& corpus) {
  ModelFiles(corpus / "model_file_fuzzer");
  PairsFiles(corpus / "pairs_file_fuzzer");

  Hdf5File(corpus / "hdf5_descriptors_fuzzer" / "float32.h5",
           false,
           {"a.jpg", "b.jpg"});
  Hdf5File(corpus / "hdf5_descriptors_fuzzer" / "float16_nested.h5",
           true,
           {"dir/c.jpg"});

  const fs::path npy = corpus / "npy_descriptors_fuzzer";
  Put(npy / "f4_v1.npy", Join({Npy(1, "<f4", 2, 3), "a.jpg\nb.jpg\n"}));
  Put(npy / "f2_v2.npy", Join({Npy(2, "<f2", 1, 4), "x.png\n"}));
  Put(npy / "f8_v3.npy", Join({Npy(3, "<f8", 3, 1), "a\r\nb\r\nc\r\n"}));

  const fs::path text = corpus / "text_descriptors_fuzzer";
  Put(text / "three.txt", "# name v1 v2 v3\na.jpg 1 0.5 -2\nb.jpg 0 1e-3 3\n");
  Put(text / "one.txt", "dir/c.png nan\n\n");

  const Reconstruction model = SmallModel();
  const fs::path binary = corpus / "sparse_model_binary_fuzzer";
  Put(binary / "small", SparseModelFiles(model, true, true));
  Put(binary / "empty", SparseModelFiles(Reconstruction(), true, true));
  const fs::path text_model = corpus / "sparse_model_text_fuzzer";
  Put(text_model / "small", SparseModelFiles(model, false, true));
  Put(text_model / "no_points", SparseModelFiles(model, false, false));

  const std::vector<std::string> names = {
      "img1.jpg", "img2.jpg", "img3.jpg", "unregistered.jpg"};
  const BundlerFile bundle = ReconstructionToBundler(model, names);
  TemporaryDirectory dir("colmap_gcn_corpus");
  const std::string bundle_path = JoinPaths(dir.Path(), "bundle.out");
  test::WriteBundlerFile(bundle_path, bundle);
  Put(corpus / "bundler_fuzzer" / "bundle.out", ReadTextFile(bundle_path));
  Put(corpus / "bundler_fuzzer" / "empty.out", "# Bundle file v0.3\n0 0\n");
}

}  // namespace
}  // namespace colmap_gcn

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <corpus dir>\n", argv[0]);
    return 2;
  }
  try {
    colmap_gcn::Generate(argv[1]);
  } catch (const colmap_gcn::Error& error) {
    std::fprintf(stderr, "ERROR: %s\n", error.what());
    return 1;
  }
  return 0;
}
