// CNN embedding options and the model stored with a GCN model: centring,
// PCA-whitening (trained on collections), the VLAD ⊕ CNN concatenation.
//
// Model bytes (CnnEmbeddingModel::Serialize):
//   char[8] "CGCNCNNM", u32 version (1), str network_name, u64 checksum,
//   i32 descriptor_dim, i32 max_image_size, i32 size_multiple, f64 scale,
//   f64 mean, u8 swap_rb, f64 gem_p, u8 center, i32 pca_out, i32 pca_in,
//   f32 pca mean[in], projection[out x in], eigenvalues[out], then u64
//   HashBytes of everything before; str = u64 length + bytes.
#include "retrieval/cnn_embedding.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "retrieval/hash.h"
#include "util/binary_io.h"
#include "util/error.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

const char kModelMagic[8] = {'C', 'G', 'C', 'N', 'C', 'N', 'N', 'M'};
const uint32_t kVersion = 1;

std::string FileName(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

void CnnEmbeddingOptions::Check() const {
  CHECK_OPTION_GE(size_multiple, 1);
  CHECK_OPTION_GE(max_image_size, size_multiple);
  CHECK_OPTION_GT(scale, 0.0);
  CHECK_OPTION_RANGE(mean, 0.0, 255.0);
  CHECK_OPTION_GE(gem_p, 1.0);
  CHECK_OPTION_GE(pca_dim, 0);
  CHECK_OPTION_GE(pca_shrinkage, 0.0);
  CHECK_OPTION_GE(batch_size, 1);
  CHECK_OPTION_NUM_THREADS(num_threads);
  CHECK_OPTION_GE(progress_every, 0);
}

void CnnEmbeddingOverrides::Check() const {
  CHECK_OPTION_UNSET_OR_GE(size_multiple, -1, "the model's value", 1);
  CHECK_OPTION_UNSET_OR_GE(max_image_size, -1, "the model's value", 1);
  CHECK_OPTION(
      scale, scale == -1 || scale > 0, "be -1 (the model's value) or > 0");
  CHECK_OPTION_UNSET_OR_RANGE(mean, -1, "the model's value", 0.0, 255.0);
  CHECK_OPTION_UNSET_OR_RANGE(swap_rb, -1, "the model's value", 0, 1);
  CHECK_OPTION_UNSET_OR_GE(gem_p, -1, "the model's value", 1.0);
  CHECK_OPTION_UNSET_OR_RANGE(center, -1, "the model's value", 0, 1);
}

CnnEmbeddingOptions CnnEmbeddingOverrides::ApplyTo(
    CnnEmbeddingOptions options) const {
  if (max_image_size != -1) options.max_image_size = max_image_size;
  if (size_multiple != -1) options.size_multiple = size_multiple;
  if (scale != -1) options.scale = scale;
  if (mean != -1) options.mean = mean;
  if (swap_rb != -1) options.swap_rb = swap_rb == 1;
  if (gem_p != -1) options.gem_p = gem_p;
  if (center != -1) options.center = center == 1;
  return options;
}

void CnnEmbeddingOverrides::CheckAgainst(const CnnEmbeddingOptions& model,
                                         const std::string& prefix) const {
  auto check = [&](bool set, double value, double expected, const char* name) {
    if (set && value != expected) {
      ThrowError("the GCN model was trained with ",
                 prefix,
                 name,
                 " ",
                 expected,
                 " but it is ",
                 value,
                 "; leave it unset (-1) or train a model with it");
    }
  };
  check(max_image_size != -1,
        max_image_size,
        model.max_image_size,
        "max_image_size");
  check(
      size_multiple != -1, size_multiple, model.size_multiple, "size_multiple");
  check(scale != -1, scale, model.scale, "scale");
  check(mean != -1, mean, model.mean, "mean");
  check(swap_rb != -1, swap_rb, model.swap_rb ? 1 : 0, "swap_rb");
  check(gem_p != -1, gem_p, model.gem_p, "gem_p");
  check(center != -1, center, model.center ? 1 : 0, "center");
}

void AddCnnEmbeddingOverrideOptions(OptionManager* manager,
                                    const std::string& prefix,
                                    CnnEmbeddingOverrides* overrides) {
  manager->AddDefaultOption(prefix + "max_image_size",
                            &overrides->max_image_size,
                            "CNN input long side; -1: the model's (knn: 512)");
  manager->AddDefaultOption(prefix + "size_multiple",
                            &overrides->size_multiple,
                            "CNN input sides multiple of; -1: model's (32)");
  manager->AddDefaultOption(prefix + "scale",
                            &overrides->scale,
                            "(pixel - mean) * scale; -1: model's (1/127.5)");
  manager->AddDefaultOption(prefix + "mean",
                            &overrides->mean,
                            "subtracted from pixels; -1: model's (127.5)");
  manager->AddDefaultOption(prefix + "swap_rb",
                            &overrides->swap_rb,
                            "1: RGB input, 0: BGR; -1: model's (1)");
  manager->AddDefaultOption(prefix + "gem_p",
                            &overrides->gem_p,
                            "GeM pooling exponent; -1: model's (3)");
  manager->AddDefaultOption(prefix + "center",
                            &overrides->center,
                            "1: subtract the collection mean; -1: model's (1)");
}

EmbeddingMatrix CnnEmbeddingModel::Apply(const FloatMatrix& raw) const {
  THROW_CHECK(raw.cols() == descriptor_dim);
  FloatMatrix x = raw;
  auto normalise = [](FloatMatrix* rows) {
    for (Eigen::Index i = 0; i < rows->rows(); ++i) {
      const float norm = rows->row(i).norm();
      if (norm > 0) rows->row(i) /= norm;
    }
  };
  if (options.center && x.rows() > 0) {
    const Eigen::RowVectorXf mean = x.colwise().mean();
    x.rowwise() -= mean;
    if (HasPca()) normalise(&x);
  }
  if (HasPca()) x = pca.Apply(x);
  normalise(&x);
  return x;
}

void CnnEmbeddingModel::CheckNetwork(const CnnNetwork& network,
                                     const std::string& flag) const {
  if (network.NetworkChecksum() != network_checksum) {
    ThrowError("the model was trained on ",
               network_name,
               " (checksum ",
               FormatChecksum(network_checksum),
               ") but ",
               flag,
               " is ",
               network.Options().onnx_path,
               " (checksum ",
               FormatChecksum(network.NetworkChecksum()),
               ")");
  }
  if (network.DescriptorDim() != descriptor_dim) {
    ThrowError("the model expects ",
               descriptor_dim,
               "-dimensional descriptors from ",
               network_name,
               " but the network gives ",
               network.DescriptorDim());
  }
}

std::string CnnEmbeddingModel::Serialize() const {
  ByteWriter writer;
  writer.Bytes().append(kModelMagic, 8);
  writer.Put<uint32_t>(kVersion);
  writer.PutString(network_name);
  writer.Put<uint64_t>(network_checksum);
  writer.Put<int32_t>(descriptor_dim);
  writer.Put<int32_t>(options.max_image_size);
  writer.Put<int32_t>(options.size_multiple);
  writer.Put<double>(options.scale);
  writer.Put<double>(options.mean);
  writer.Put<uint8_t>(options.swap_rb ? 1 : 0);
  writer.Put<double>(options.gem_p);
  writer.Put<uint8_t>(options.center ? 1 : 0);
  writer.Put<int32_t>(pca.OutputDim());
  writer.Put<int32_t>(HasPca() ? pca.InputDim() : 0);
  if (HasPca()) {
    writer.PutFloats(pca.mean.data(), pca.mean.size());
    writer.PutFloats(pca.projection.data(), pca.projection.size());
    writer.PutFloats(pca.eigenvalues.data(), pca.eigenvalues.size());
  }
  const uint64_t hash = HashBytes(writer.Bytes().data(), writer.Bytes().size());
  writer.Put<uint64_t>(hash);
  return writer.Bytes();
}

CnnEmbeddingModel CnnEmbeddingModel::Deserialize(const std::string& bytes,
                                                 const std::string& source) {
  if (bytes.size() < 8 + 4 + 8 ||
      std::memcmp(bytes.data(), kModelMagic, 8) != 0) {
    ThrowError(source, " is not a CNN embedding configuration (bad magic)");
  }
  uint64_t stored_hash;
  std::memcpy(&stored_hash, bytes.data() + bytes.size() - 8, 8);
  if (HashBytes(bytes.data(), bytes.size() - 8) != stored_hash) {
    ThrowError(source, " is corrupt (checksum mismatch)");
  }
  ByteReader reader(bytes, 0, bytes.size() - 8, [&source](size_t) {
    ThrowError(source, " is truncated");
  });
  reader.Get<uint64_t>();  // magic
  const uint32_t version = reader.Get<uint32_t>();
  if (version != kVersion) {
    ThrowError(source, " has unsupported version ", version);
  }
  CnnEmbeddingModel model;
  model.network_name = reader.GetString();
  model.network_checksum = reader.Get<uint64_t>();
  model.descriptor_dim = reader.Get<int32_t>();
  model.options.max_image_size = reader.Get<int32_t>();
  model.options.size_multiple = reader.Get<int32_t>();
  model.options.scale = reader.Get<double>();
  model.options.mean = reader.Get<double>();
  model.options.swap_rb = reader.Get<uint8_t>() != 0;
  model.options.gem_p = reader.Get<double>();
  model.options.center = reader.Get<uint8_t>() != 0;
  const int pca_out = reader.Get<int32_t>();
  const int pca_in = reader.Get<int32_t>();
  if (model.descriptor_dim < 1 || pca_out < 0 ||
      (pca_out > 0 && pca_in != model.descriptor_dim) ||
      (pca_out == 0 && pca_in != 0)) {
    ThrowError(source, " is malformed (dimensions)");
  }
  model.options.pca_dim = pca_out;
  if (pca_out > 0) {
    model.pca.mean.resize(pca_in);
    model.pca.projection.resize(pca_out, pca_in);
    model.pca.eigenvalues.resize(pca_out);
    reader.GetFloats(model.pca.mean.data(), pca_in);
    reader.GetFloats(model.pca.projection.data(),
                     static_cast<size_t>(pca_out) * pca_in);
    reader.GetFloats(model.pca.eigenvalues.data(), pca_out);
  }
  if (reader.Position() != bytes.size() - 8) {
    ThrowError(source, " has trailing bytes");
  }
  return model;
}

CnnEmbeddingModel MakeCnnEmbeddingModel(const CnnNetwork& network) {
  CnnEmbeddingModel model;
  model.network_name = FileName(network.Options().onnx_path);
  model.network_checksum = network.NetworkChecksum();
  model.descriptor_dim = network.DescriptorDim();
  model.options = network.Options();
  model.options.onnx_path = "";
  model.options.pca_dim = 0;
  return model;
}

CnnEmbeddingModel TrainCnnEmbeddingModel(
    const CnnNetwork& network, const std::vector<FloatMatrix>& collections) {
  CnnEmbeddingModel model = MakeCnnEmbeddingModel(network);
  const CnnEmbeddingOptions& options = network.Options();
  if (options.pca_dim == 0) return model;
  Eigen::Index num_rows = 0;
  for (const auto& collection : collections) num_rows += collection.rows();
  FloatMatrix samples(num_rows, model.descriptor_dim);
  Eigen::Index offset = 0;
  for (const auto& collection : collections) {
    // Centred (and normalised) per collection, as Apply will at test time.
    samples.middleRows(offset, collection.rows()) = model.Apply(collection);
    offset += collection.rows();
  }
  PcaOptions pca_options;
  pca_options.dim = options.pca_dim;
  pca_options.shrinkage = options.pca_shrinkage;
  model.pca = TrainPcaWhitening(samples, pca_options);
  model.options.pca_dim = model.pca.OutputDim();
  model.options.pca_shrinkage = options.pca_shrinkage;
  return model;
}

EmbeddingMatrix ConcatenateEmbeddings(const EmbeddingMatrix& a,
                                      const EmbeddingMatrix& b) {
  THROW_CHECK(a.rows() == b.rows());
  EmbeddingMatrix result(a.rows(), a.cols() + b.cols());
  const float half = static_cast<float>(1.0 / std::sqrt(2.0));
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const float norm_a = a.row(i).norm();
    const float norm_b = b.row(i).norm();
    result.row(i).head(a.cols()) =
        norm_a > 0 ? Eigen::RowVectorXf(a.row(i) * (half / norm_a))
                   : Eigen::RowVectorXf::Zero(a.cols());
    result.row(i).tail(b.cols()) =
        norm_b > 0 ? Eigen::RowVectorXf(b.row(i) * (half / norm_b))
                   : Eigen::RowVectorXf::Zero(b.cols());
  }
  return result;
}

}  // namespace colmap_gcn
