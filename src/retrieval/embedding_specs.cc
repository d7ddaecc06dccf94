// The built-in embeddings (COLMAP_GCN_EMBEDDINGS): VLAD, the ONNX CNN, both
// concatenated, and imported descriptors. They share this file because
// vlad+onnx is made of the other two.

#include <cstring>

#include "retrieval/cnn_embedding.h"
#include "retrieval/descriptor_import.h"
#include "retrieval/embedding_cache.h"
#include "retrieval/embedding_spec.h"
#include "retrieval/global_descriptors.h"
#include "retrieval/model_embedding.h"
#include "retrieval/vlad.h"
#include "util/error.h"
#include "util/string.h"

namespace colmap_gcn {

namespace {

const char kConcatenatedMagic[8] = {'C', 'G', 'C', 'N', 'V', '+', 'O', 'N'};

void SplitConcatenatedBlob(const std::string& blob,
                           std::string* vlad,
                           std::string* cnn) {
  auto fail = [] {
    ThrowError("the GCN model's vlad+onnx embedding is malformed");
  };
  if (blob.size() < 8 + 16 || std::memcmp(blob.data(), kConcatenatedMagic, 8)) {
    fail();
  }
  size_t pos = 8;
  for (std::string* part : {vlad, cnn}) {
    uint64_t size;
    if (blob.size() - pos < 8) fail();
    std::memcpy(&size, blob.data() + pos, 8);
    pos += 8;
    if (size > blob.size() - pos) fail();
    *part = blob.substr(pos, size);
    pos += size;
  }
  if (pos != blob.size()) fail();
}

// RootSIFT -> VLAD -> PCA-whitening of the database's features, cached in
// "<database>.gcn-embedding.bin" per image feature hash.
class VladDatabaseEmbedding : public DatabaseEmbedding {
 public:
  VladDatabaseEmbedding(VladEmbedding vlad, bool use_cache, int num_threads)
      : vlad_(std::move(vlad)),
        use_cache_(use_cache),
        num_threads_(num_threads) {}

  int OutputDim() const { return vlad_.OutputDim(); }

  EmbeddingMatrix EmbedDatabase(
      const Database& database,
      const std::string& /*image_path*/,
      const std::string& /*image_cache_path*/,
      std::vector<image_t>* image_ids) const override {
    return ComputeDatabaseEmbeddings(
        database,
        vlad_,
        image_ids,
        use_cache_ ? DefaultEmbeddingCachePath(database.Path()) : "",
        num_threads_);
  }

 private:
  VladEmbedding vlad_;
  bool use_cache_;
  int num_threads_;
};

// An ONNX CNN on the image files (OpenCV DNN; GeM), then centring and PCA
// over the collection.
class CnnDatabaseEmbedding : public DatabaseEmbedding {
 public:
  CnnDatabaseEmbedding(CnnEmbeddingModel model,
                       std::unique_ptr<CnnNetwork> network)
      : model_(std::move(model)), network_(std::move(network)) {}

  EmbeddingMatrix EmbedDatabase(
      const Database& database,
      const std::string& image_path,
      const std::string& image_cache_path,
      std::vector<image_t>* image_ids) const override {
    return ComputeDatabaseCnnDescriptors(
        database, *network_, image_path, image_cache_path, image_ids);
  }

  EmbeddingMatrix Finalize(const EmbeddingMatrix& rows) const override {
    return model_.Apply(rows);
  }

 private:
  CnnEmbeddingModel model_;
  std::unique_ptr<CnnNetwork> network_;
};

// Both: VLAD rows beside raw CNN rows until the collection step, then each
// half L2-normalised and scaled by 1/sqrt(2).
class VladOnnxDatabaseEmbedding : public DatabaseEmbedding {
 public:
  VladOnnxDatabaseEmbedding(std::unique_ptr<VladDatabaseEmbedding> vlad,
                            std::unique_ptr<CnnDatabaseEmbedding> cnn)
      : vlad_(std::move(vlad)), cnn_(std::move(cnn)) {}

  EmbeddingMatrix EmbedDatabase(
      const Database& database,
      const std::string& image_path,
      const std::string& image_cache_path,
      std::vector<image_t>* image_ids) const override {
    const EmbeddingMatrix vlad =
        vlad_->EmbedDatabase(database, image_path, image_cache_path, image_ids);
    const EmbeddingMatrix raw =
        cnn_->EmbedDatabase(database, image_path, image_cache_path, image_ids);
    EmbeddingMatrix both(raw.rows(), vlad.cols() + raw.cols());
    both << vlad, raw;
    return both;
  }

  EmbeddingMatrix Finalize(const EmbeddingMatrix& rows) const override {
    const int vlad_dim = vlad_->OutputDim();
    return ConcatenateEmbeddings(
        rows.leftCols(vlad_dim),
        cnn_->Finalize(rows.rightCols(rows.cols() - vlad_dim)));
  }

 private:
  std::unique_ptr<VladDatabaseEmbedding> vlad_;
  std::unique_ptr<CnnDatabaseEmbedding> cnn_;
};

// Global descriptors from a file (hloc HDF5, npy, txt), matched to the
// database's images by name.
class ImportedDatabaseEmbedding : public DatabaseEmbedding {
 public:
  explicit ImportedDatabaseEmbedding(std::string descriptor_path)
      : descriptor_path_(std::move(descriptor_path)) {}

  EmbeddingMatrix EmbedDatabase(
      const Database& database,
      const std::string& /*image_path*/,
      const std::string& /*image_cache_path*/,
      std::vector<image_t>* image_ids) const override {
    return MatchDescriptorsToImages(ReadGlobalDescriptors(descriptor_path_),
                                    database.ReadAllImages(),
                                    image_ids);
  }

 private:
  std::string descriptor_path_;
};

std::unique_ptr<VladDatabaseEmbedding> LoadVlad(
    const std::string& blob, const ModelEmbeddingOptions& options) {
  return std::make_unique<VladDatabaseEmbedding>(
      VladEmbedding::Deserialize(blob, "the GCN model's embedding"),
      options.use_vlad_cache,
      options.num_threads);
}

// The model's CNN, checked against the user's network and preprocessing.
std::unique_ptr<CnnDatabaseEmbedding> LoadCnn(
    const std::string& blob, const ModelEmbeddingOptions& options) {
  CnnEmbeddingModel model =
      CnnEmbeddingModel::Deserialize(blob, "the GCN model's embedding");
  const EmbeddingOptions& asked = options.embedding;
  if (asked.onnx_path.empty()) {
    ThrowError("the GCN model embeds images with the ONNX network ",
               model.network_name,
               " (checksum ",
               FormatChecksum(model.network_checksum),
               "); pass it with ",
               options.onnx_flag);
  }
  asked.onnx.CheckAgainst(model.options, "--GcnMatching.onnx_");
  CnnEmbeddingOptions cnn = model.options;
  cnn.onnx_path = asked.onnx_path;
  cnn.batch_size = asked.onnx_batch_size;
  cnn.num_threads = options.num_threads;
  cnn.progress_every = options.progress_every;
  auto network = std::make_unique<CnnNetwork>(cnn);
  model.CheckNetwork(*network, options.onnx_flag);
  return std::make_unique<CnnDatabaseEmbedding>(std::move(model),
                                                std::move(network));
}

// knn's VLAD: the model named by embedding_path, or one trained on the
// database itself.
std::unique_ptr<VladDatabaseEmbedding> BuildVlad(
    const Database& database, const GlobalDescriptorOptions& options) {
  return std::make_unique<VladDatabaseEmbedding>(
      options.embedding_path.empty()
          ? LoadOrTrainSelfEmbedding(database, options.vlad, options.use_cache)
          : VladEmbedding::Read(options.embedding_path),
      options.use_cache,
      options.num_threads);
}

// knn's CNN: centred on the database, no PCA.
std::unique_ptr<CnnDatabaseEmbedding> BuildCnn(
    const GlobalDescriptorOptions& options) {
  CnnEmbeddingOptions cnn = options.cnn;
  cnn.num_threads = options.num_threads;
  auto network = std::make_unique<CnnNetwork>(cnn);
  CnnEmbeddingModel model = MakeCnnEmbeddingModel(*network);
  return std::make_unique<CnnDatabaseEmbedding>(std::move(model),
                                                std::move(network));
}

}  // namespace

GcnEmbeddingConfig MakeEmbeddingConfig(const VladEmbedding* vlad,
                                       const CnnEmbeddingModel* cnn) {
  THROW_CHECK(vlad != nullptr || cnn != nullptr);
  GcnEmbeddingConfig config;
  if (cnn == nullptr) {
    config.type = "vlad";
    config.dim = vlad->OutputDim();
    config.blob = vlad->Serialize();
  } else if (vlad == nullptr) {
    config.type = "onnx";
    config.dim = cnn->OutputDim();
    config.blob = cnn->Serialize();
  } else {
    config.type = "vlad+onnx";
    config.dim = vlad->OutputDim() + cnn->OutputDim();
    config.blob.assign(kConcatenatedMagic, 8);
    for (const std::string& part : {vlad->Serialize(), cnn->Serialize()}) {
      const uint64_t size = part.size();
      config.blob.append(reinterpret_cast<const char*>(&size), 8);
      config.blob += part;
    }
  }
  return config;
}

EmbeddingSpec VladEmbeddingSpec() {
  EmbeddingSpec spec;
  spec.load = [](const GcnEmbeddingConfig& config,
                 const ModelEmbeddingOptions& options) {
    return std::unique_ptr<DatabaseEmbedding>(LoadVlad(config.blob, options));
  };
  spec.build = [](const Database& database,
                  const GlobalDescriptorOptions& options) {
    return std::unique_ptr<DatabaseEmbedding>(BuildVlad(database, options));
  };
  return spec;
}

EmbeddingSpec OnnxEmbeddingSpec() {
  EmbeddingSpec spec;
  spec.load = [](const GcnEmbeddingConfig& config,
                 const ModelEmbeddingOptions& options) {
    return std::unique_ptr<DatabaseEmbedding>(LoadCnn(config.blob, options));
  };
  spec.build = [](const Database& /*database*/,
                  const GlobalDescriptorOptions& options) {
    return std::unique_ptr<DatabaseEmbedding>(BuildCnn(options));
  };
  return spec;
}

EmbeddingSpec VladOnnxEmbeddingSpec() {
  EmbeddingSpec spec;
  spec.load = [](const GcnEmbeddingConfig& config,
                 const ModelEmbeddingOptions& options)
      -> std::unique_ptr<DatabaseEmbedding> {
    std::string vlad_blob;
    std::string cnn_blob;
    SplitConcatenatedBlob(config.blob, &vlad_blob, &cnn_blob);
    auto vlad = LoadVlad(vlad_blob, options);
    return std::make_unique<VladOnnxDatabaseEmbedding>(
        std::move(vlad), LoadCnn(cnn_blob, options));
  };
  spec.build = [](const Database& database,
                  const GlobalDescriptorOptions& options)
      -> std::unique_ptr<DatabaseEmbedding> {
    auto cnn = BuildCnn(options);
    return std::make_unique<VladOnnxDatabaseEmbedding>(
        BuildVlad(database, options), std::move(cnn));
  };
  return spec;
}

EmbeddingSpec ImportedEmbeddingSpec() {
  EmbeddingSpec spec;
  spec.load = [](const GcnEmbeddingConfig& config,
                 const ModelEmbeddingOptions& options) {
    if (options.embedding.descriptor_path.empty()) {
      ThrowError("the GCN model was trained on imported descriptors (",
                 config.type,
                 "); pass them with --GcnMatching.descriptor_path");
    }
    return std::unique_ptr<DatabaseEmbedding>(
        std::make_unique<ImportedDatabaseEmbedding>(
            options.embedding.descriptor_path));
  };
  spec.build = [](const Database& /*database*/,
                  const GlobalDescriptorOptions& options) {
    return std::unique_ptr<DatabaseEmbedding>(
        std::make_unique<ImportedDatabaseEmbedding>(options.descriptor_path));
  };
  return spec;
}

}  // namespace colmap_gcn
