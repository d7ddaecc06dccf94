#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "retrieval/kmeans.h"
#include "retrieval/pca.h"
#include "scene/database.h"

namespace colmap_gcn {

// RootSIFT (Arandjelovic & Zisserman 2012) of COLMAP's uint8 SIFT rows: L1
// normalise, then element-wise sqrt, so that dot products of the results are
// Hellinger kernels of the originals. All-zero rows stay zero.
FloatMatrix RootSift(const FeatureDescriptors& descriptors);

struct VladOptions {
  // Visual words of the k-means codebook (capped by training descriptors).
  int num_words = 64;

  // Output dimension after PCA-whitening (capped by the PCA rank, <= N - 1
  // for N training images).
  int dim = 256;

  // Whitening shrinkage (PcaOptions::shrinkage): 0 is full whitening. A
  // model trained on a separate set of databases can use 0; one trained on
  // the target database itself must not (see PcaOptions), so
  // self-training uses self_training_shrinkage.
  double shrinkage = 0.1;
  double self_training_shrinkage = 3.0;

  // k-means runs on at most this many descriptors, a deterministic strided
  // subsample over all images.
  int max_training_descriptors = 100000;

  // Lloyd iterations of the codebook k-means.
  int kmeans_iterations = 25;

  // PCA uses the raw VLADs of at most this many images (evenly strided).
  int max_pca_images = 4096;

  // Seed of k-means++.
  uint32_t seed = 0;

  // Threads for training; -1 uses all cores. Results do not depend on it.
  int num_threads = -1;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// The embedding f(I) of the paper's Eq. 1 built from COLMAP's own features:
// RootSIFT -> VLAD over a k-means codebook (intra-normalisation, signed
// square root, L2) -> PCA-whitening -> L2. Immutable once built; Embed is
// thread-safe.
class VladEmbedding {
 public:
  VladEmbedding() = default;
  VladEmbedding(FloatMatrix codebook, PcaWhitening pca);

  int NumWords() const { return static_cast<int>(codebook_.rows()); }
  int DescriptorDim() const { return static_cast<int>(codebook_.cols()); }
  int VladDim() const { return NumWords() * DescriptorDim(); }
  int OutputDim() const { return pca_.OutputDim(); }
  const FloatMatrix& Codebook() const { return codebook_; }
  const PcaWhitening& Pca() const { return pca_; }

  // Identifies the model (hash of its serialised bytes); caches key on it.
  uint64_t Checksum() const { return checksum_; }

  // The normalised VLAD (VladDim()) of one image's descriptors; all zero
  // when the image has none.
  Eigen::RowVectorXf ComputeVlad(const FeatureDescriptors& descriptors) const;

  // The final unit-length embedding (OutputDim()); all zero when the image
  // has no descriptors, so it is similar to nothing.
  Eigen::RowVectorXf Embed(const FeatureDescriptors& descriptors) const;

  // Versioned, checksummed binary file (see vlad_io.cc). Read throws Error
  // on a missing, truncated, foreign or corrupt file.
  void Write(const std::string& path) const;
  static VladEmbedding Read(const std::string& path);

  // The file's bytes, e.g. to embed the model in a GCN model file;
  // Deserialize validates them like Read ("source" names them in errors).
  std::string Serialize() const;
  static VladEmbedding Deserialize(const std::string& bytes,
                                   const std::string& source);

  // The serialised model without the trailing checksum.
  std::string SerializePayload() const;

 private:
  FloatMatrix codebook_;  // num_words x 128, in RootSIFT space
  Eigen::VectorXf codebook_norms_;
  PcaWhitening pca_;
  uint64_t checksum_ = 0;
};

// Trains codebook and whitening on the descriptors of the given databases
// (images of all databases together). shrinkage is options.shrinkage.
VladEmbedding TrainVladEmbedding(const std::vector<std::string>& database_paths,
                                 const VladOptions& options);

// The same on one open database with an explicit shrinkage (used to
// self-train on the target database).
VladEmbedding TrainVladEmbedding(const std::vector<const Database*>& databases,
                                 const VladOptions& options,
                                 double shrinkage);

}  // namespace colmap_gcn
