#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "retrieval/embedding_cache.h"
#include "retrieval/knn.h"
#include "retrieval/pca.h"
#include "scene/database.h"

namespace colmap_gcn {

class OptionManager;

// A global descriptor from a CNN run by OpenCV DNN on the image files: the
// network (ONNX) maps an image to a feature map 1 x C x h x w, pooled by
// generalised mean (GeM), or directly to a vector 1 x C. Defaults are those
// of ImageNet MobileNetV2 cut before its pooling (docs/retrieval.md).
struct CnnEmbeddingOptions {
  // The ONNX network (opset <= 11 for Debian's OpenCV 4.6).
  std::string onnx_path = "";

  // Long side of the network input in pixels: every image is resized to it,
  // keeping its aspect, each side rounded to a multiple of size_multiple.
  int max_image_size = 512;

  // The network's input sides must be multiples of this (its total stride:
  // 32 for MobileNetV2, 14 for a ViT with 14-pixel patches).
  int size_multiple = 32;

  // Input = (pixel - mean) * scale on each channel (cv::dnn::blobFromImage);
  // swap_rb feeds RGB instead of OpenCV's BGR.
  double scale = 1.0 / 127.5;
  double mean = 127.5;
  bool swap_rb = true;

  // GeM exponent for feature-map outputs: (mean_hw max(x, 1e-6)^p)^(1/p)
  // per channel, then L2; 1 is average pooling. Vector outputs are used as
  // they are.
  double gem_p = 3.0;

  // Subtract the collection's mean descriptor and re-normalise: removes the
  // direction all photos share (unsupervised; raises cross-scene AP).
  bool center = true;

  // PCA-whitening learned on the training collection of a GCN model, so
  // the GCN's input stays as small as with VLAD; 0 keeps the network's C
  // dimensions. Not used for kNN pairing (no training collection).
  int pca_dim = 256;

  // Whitening shrinkage (PcaOptions::shrinkage) of that PCA.
  double pca_shrinkage = 1.0;

  // Images of equal input size forwarded together (a batch never spans
  // sizes); results do not depend on it.
  int batch_size = 1;

  // Worker threads, each with its own copy of the network running
  // single-threaded, so that the result does not depend on the count; -1
  // uses all cores.
  int num_threads = -1;

  // > 0: progress on stderr (util/logging.h ProgressLogger); 0 is silent.
  int progress_every = 50;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// CNN options as users set them on a command line (--GcnMatching.onnx_*):
// each unset value (-1) is the model's (GCN pairing) or CnnEmbeddingOptions'
// default (kNN pairing); a GCN model refuses set values that differ from
// its own.
struct CnnEmbeddingOverrides {
  int max_image_size = -1;
  int size_multiple = -1;
  double scale = -1;
  double mean = -1;
  int swap_rb = -1;  // -1, 0 or 1
  double gem_p = -1;
  int center = -1;  // -1, 0 or 1

  // Throws OptionError naming the first invalid field.
  void Check() const;

  // `options` with the set values replaced.
  CnnEmbeddingOptions ApplyTo(CnnEmbeddingOptions options) const;

  // Throws Error naming the first set value that differs from `model`'s:
  // "the GCN model was trained with <prefix>max_image_size 512 but it is
  // 768".
  void CheckAgainst(const CnnEmbeddingOptions& model,
                    const std::string& prefix) const;
};

// Binds --<prefix>max_image_size, size_multiple, scale, mean, swap_rb, gem_p
// and center (prefix e.g. "GcnMatching.onnx_") to *overrides.
void AddCnnEmbeddingOverrideOptions(OptionManager* manager,
                                    const std::string& prefix,
                                    CnnEmbeddingOverrides* overrides);

// The network input size of an image of width x height: long side
// max_image_size, aspect kept, sides rounded to multiples of size_multiple
// (at least one multiple).
std::pair<int, int> CnnInputSize(int width,
                                 int height,
                                 const CnnEmbeddingOptions& options);

// 64-bit checksum of a file's bytes (retrieval/hash.h), as 16 hex digits by
// FormatChecksum.
uint64_t FileChecksum(const std::string& path);
std::string FormatChecksum(uint64_t checksum);

// The network, loaded once (one copy per worker thread). Thread-compatible:
// Describe* calls must not overlap.
class CnnNetwork {
 public:
  // Throws Error (one line) for a missing, unreadable or non-ONNX file, or
  // a network whose output is neither 1 x C x h x w nor 1 x C.
  explicit CnnNetwork(const CnnEmbeddingOptions& options);
  ~CnnNetwork();

  const CnnEmbeddingOptions& Options() const { return options_; }
  uint64_t NetworkChecksum() const { return checksum_; }
  // C, the raw descriptor dimension.
  int DescriptorDim() const { return descriptor_dim_; }
  // Identifies everything a raw descriptor depends on (network bytes and
  // preprocessing/pooling options); cache entries are keyed on it.
  uint64_t ConfigKey() const;

  // Raw (pooled, L2-normalised, not centred) descriptor of an encoded image
  // file's bytes; `source` names the image in errors.
  Eigen::RowVectorXf DescribeEncoded(const std::string& bytes,
                                     const std::string& source) const;

  // One row per item, in order; items are (bytes, source). Runs on
  // options.num_threads workers; identical for any thread count.
  FloatMatrix DescribeEncodedBatch(
      const std::vector<std::pair<std::string, std::string>>& items) const;

 private:
  struct Impl;
  CnnEmbeddingOptions options_;
  uint64_t checksum_ = 0;
  int descriptor_dim_ = 0;
  std::unique_ptr<Impl> impl_;
};

// "<database_path>.gcn-cnn-embedding.bin".
std::string DefaultCnnCachePath(const std::string& database_path);

// Raw CNN descriptors of all database images (ascending image id, in
// *image_ids), read from image_path/<name>. With a non-empty cache_path, an
// image whose file bytes and network configuration are unchanged reuses its
// cached descriptor; the cache is rewritten every ~30 s while embedding, so
// an interrupted run resumes. A missing, stale or corrupt cache only costs
// time. Throws Error naming an image that cannot be read or decoded.
FloatMatrix ComputeDatabaseCnnDescriptors(const Database& database,
                                          const CnnNetwork& network,
                                          const std::string& image_path,
                                          const std::string& cache_path,
                                          std::vector<image_t>* image_ids,
                                          EmbeddingCacheStats* stats = nullptr);

// What turns a collection's raw descriptors into embeddings, stored in a GCN
// model (GcnEmbeddingConfig type "onnx", blob = Serialize()): the network's
// identity and configuration, optional centring and PCA-whitening.
struct CnnEmbeddingModel {
  std::string network_name;  // the ONNX file's name, for messages
  uint64_t network_checksum = 0;
  int descriptor_dim = 0;
  // The preprocessing and pooling fields (max_image_size, size_multiple,
  // scale, mean, swap_rb, gem_p, center) are part of the model; paths,
  // threads and progress are not.
  CnnEmbeddingOptions options;
  PcaWhitening pca;  // empty (OutputDim() 0): no projection

  bool HasPca() const { return pca.OutputDim() > 0; }
  int OutputDim() const { return HasPca() ? pca.OutputDim() : descriptor_dim; }

  // Rows of one collection: centred by their own mean (options.center),
  // re-normalised, projected (PCA), L2-normalised.
  EmbeddingMatrix Apply(const FloatMatrix& raw) const;

  // Throws Error unless `network` has this model's checksum and
  // configuration; `flag` names the option that chose the network.
  void CheckNetwork(const CnnNetwork& network, const std::string& flag) const;

  // Versioned, checksummed bytes; Deserialize throws Error on bad bytes
  // (`source` names them).
  std::string Serialize() const;
  static CnnEmbeddingModel Deserialize(const std::string& bytes,
                                       const std::string& source);
};

// The model of `network` without PCA (kNN pairing).
CnnEmbeddingModel MakeCnnEmbeddingModel(const CnnNetwork& network);

// The same with PCA-whitening (options.pca_dim, pca_shrinkage) trained on
// the raw descriptors of several collections, each centred by its own mean
// first (as Apply does); pca_dim 0 gives no PCA.
CnnEmbeddingModel TrainCnnEmbeddingModel(
    const CnnNetwork& network, const std::vector<FloatMatrix>& collections);

// [a | b] with each part's rows L2-normalised and scaled by 1/sqrt(2), so
// rows stay unit length and each part contributes half the similarity (a
// part's zero row stays zero).
EmbeddingMatrix ConcatenateEmbeddings(const EmbeddingMatrix& a,
                                      const EmbeddingMatrix& b);

}  // namespace colmap_gcn
