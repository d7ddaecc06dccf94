#include "retrieval/vlad.h"

#include <algorithm>
#include <cmath>
#include <iostream>

#include "math/dense_product.h"
#include "retrieval/hash.h"
#include "retrieval/knn.h"
#include "util/error.h"
#include "util/option_check.h"
#include "util/threading.h"

namespace colmap_gcn {

void VladOptions::Check() const {
  CHECK_OPTION_GE(num_words, 1);
  CHECK_OPTION_GE(dim, 1);
  CHECK_OPTION_GE(shrinkage, 0.0);
  CHECK_OPTION_GE(self_training_shrinkage, 0.0);
  CHECK_OPTION_GE(max_training_descriptors, 1);
  CHECK_OPTION_GE(kmeans_iterations, 0);
  CHECK_OPTION_GE(max_pca_images, 2);
  CHECK_OPTION_NUM_THREADS(num_threads);
}

FloatMatrix RootSift(const FeatureDescriptors& descriptors) {
  FloatMatrix root = descriptors.cast<float>();
  for (Eigen::Index i = 0; i < root.rows(); ++i) {
    const float sum = root.row(i).sum();  // uint8 values: L1 norm
    if (sum > 0) {
      root.row(i) = (root.row(i) / sum).cwiseSqrt();
    }
  }
  return root;
}

VladEmbedding::VladEmbedding(FloatMatrix codebook, PcaWhitening pca)
    : codebook_(std::move(codebook)), pca_(std::move(pca)) {
  THROW_CHECK(codebook_.rows() > 0 && pca_.InputDim() == VladDim());
  codebook_norms_ = codebook_.rowwise().squaredNorm();
  const std::string payload = SerializePayload();
  checksum_ = HashBytes(payload.data(), payload.size());
}

Eigen::RowVectorXf VladEmbedding::ComputeVlad(
    const FeatureDescriptors& descriptors) const {
  Eigen::RowVectorXf vlad = Eigen::RowVectorXf::Zero(VladDim());
  if (descriptors.rows() == 0) {
    return vlad;
  }
  if (descriptors.cols() != DescriptorDim()) {
    ThrowError("descriptors have ",
               descriptors.cols(),
               " columns, the VLAD codebook ",
               DescriptorDim());
  }
  const FloatMatrix root = RootSift(descriptors);
  const int num_descriptors = static_cast<int>(root.rows());
  const int num_words = NumWords();
  const int dim = DescriptorDim();
  FloatMatrix products(num_descriptors, num_words);
  MultiplyABt(root.data(),
              num_descriptors,
              codebook_.data(),
              num_words,
              dim,
              products.data());
  // Residuals to the nearest word (ties: lower word index), summed per word.
  Eigen::Map<FloatMatrix> residuals(vlad.data(), num_words, dim);
  for (int i = 0; i < num_descriptors; ++i) {
    int word = 0;
    float best = codebook_norms_(0) - 2.f * products(i, 0);
    for (int w = 1; w < num_words; ++w) {
      const float value = codebook_norms_(w) - 2.f * products(i, w);
      if (value < best) {
        best = value;
        word = w;
      }
    }
    residuals.row(word) += root.row(i) - codebook_.row(word);
  }
  // Intra-normalisation stops bursty words dominating (Arandjelovic & Zisserman
  // 2013), then the signed square root and a global L2 norm.
  for (int w = 0; w < num_words; ++w) {
    const float norm = residuals.row(w).norm();
    if (norm > 0) residuals.row(w) /= norm;
  }
  vlad = vlad.array().sign() * vlad.array().abs().sqrt();
  const float norm = vlad.norm();
  if (norm > 0) vlad /= norm;
  return vlad;
}

Eigen::RowVectorXf VladEmbedding::Embed(
    const FeatureDescriptors& descriptors) const {
  if (descriptors.rows() == 0) {
    return Eigen::RowVectorXf::Zero(OutputDim());
  }
  const Eigen::RowVectorXf centred = ComputeVlad(descriptors) - pca_.mean;
  Eigen::RowVectorXf embedding(OutputDim());
  MultiplyABt(centred.data(),
              1,
              pca_.projection.data(),
              OutputDim(),
              VladDim(),
              embedding.data());
  const float norm = embedding.norm();
  if (norm > 0) embedding /= norm;
  return embedding;
}

namespace {

struct TrainingImage {
  const Database* database;
  image_t image_id;
  size_t num_descriptors;
};

// Computes fn(i, descriptors of images[i]) for the given indices: database
// reads are sequential (Database is not thread-safe), computation in
// parallel batches; fn writes only to slot i, so order does not matter.
template <typename Fn>
void ForEachImageParallel(const std::vector<TrainingImage>& images,
                          const std::vector<size_t>& indices,
                          int num_threads,
                          const Fn& fn) {
  const size_t batch_size = 4 * static_cast<size_t>(num_threads);
  for (size_t begin = 0; begin < indices.size(); begin += batch_size) {
    const size_t end = std::min(indices.size(), begin + batch_size);
    std::vector<FeatureDescriptors> batch;
    for (size_t b = begin; b < end; ++b) {
      const TrainingImage& image = images[indices[b]];
      batch.push_back(image.database->ReadDescriptors(image.image_id));
    }
    ParallelFor(static_cast<int>(begin),
                static_cast<int>(end),
                num_threads,
                [&](int b) { fn(b, batch[b - begin]); });
  }
}

}  // namespace

VladEmbedding TrainVladEmbedding(const std::vector<const Database*>& databases,
                                 const VladOptions& options,
                                 double shrinkage) {
  options.Check();
  const int num_threads = EffectiveNumThreads(options.num_threads);
  std::vector<TrainingImage> images;
  size_t total_descriptors = 0;
  for (const Database* database : databases) {
    for (const DatabaseImage& image : database->ReadAllImages()) {
      const size_t count = database->NumDescriptorsForImage(image.image_id);
      if (count == 0) continue;
      images.push_back({database, image.image_id, count});
      total_descriptors += count;
    }
  }
  if (images.size() < 2) {
    ThrowError("VLAD training needs at least 2 images with descriptors, got ",
               images.size());
  }

  // Codebook: k-means on a strided subsample of all RootSIFT descriptors.
  const size_t stride =
      (total_descriptors + options.max_training_descriptors - 1) /
      options.max_training_descriptors;
  std::vector<Eigen::RowVectorXf> sampled;
  size_t global_index = 0;
  int descriptor_dim = 0;
  for (const TrainingImage& image : images) {
    const FloatMatrix root =
        RootSift(image.database->ReadDescriptors(image.image_id));
    descriptor_dim = static_cast<int>(root.cols());
    for (Eigen::Index r = 0; r < root.rows(); ++r, ++global_index) {
      if (global_index % stride == 0) sampled.push_back(root.row(r));
    }
  }
  FloatMatrix samples(sampled.size(), descriptor_dim);
  for (size_t i = 0; i < sampled.size(); ++i) samples.row(i) = sampled[i];
  sampled.clear();
  KMeansOptions kmeans_options;
  kmeans_options.num_clusters =
      std::min<int>(options.num_words, static_cast<int>(samples.rows()));
  kmeans_options.max_iterations = options.kmeans_iterations;
  kmeans_options.seed = options.seed;
  kmeans_options.num_threads = num_threads;
  FloatMatrix codebook = KMeans(samples, kmeans_options);

  // Whitening: PCA of the raw VLADs of (a strided subset of) the images.
  const size_t num_pca =
      std::min<size_t>(images.size(), options.max_pca_images);
  std::vector<size_t> pca_indices;
  for (size_t i = 0; i < num_pca; ++i) {
    pca_indices.push_back(i * images.size() / num_pca);
  }
  PcaWhitening identity;  // placeholder so ComputeVlad can run
  identity.mean = Eigen::RowVectorXf::Zero(codebook.rows() * codebook.cols());
  identity.projection = FloatMatrix::Zero(1, identity.mean.size());
  const VladEmbedding raw(codebook, identity);
  FloatMatrix vlads(num_pca, raw.VladDim());
  ForEachImageParallel(images,
                       pca_indices,
                       num_threads,
                       [&](size_t slot, const FeatureDescriptors& descriptors) {
                         vlads.row(slot) = raw.ComputeVlad(descriptors);
                       });
  PcaOptions pca_options;
  pca_options.dim = options.dim;
  pca_options.shrinkage = shrinkage;
  return VladEmbedding(std::move(codebook),
                       TrainPcaWhitening(vlads, pca_options));
}

VladEmbedding TrainVladEmbedding(const std::vector<std::string>& database_paths,
                                 const VladOptions& options) {
  std::vector<std::unique_ptr<Database>> databases;
  std::vector<const Database*> pointers;
  for (const std::string& path : database_paths) {
    databases.push_back(std::make_unique<Database>(path));
    pointers.push_back(databases.back().get());
  }
  return TrainVladEmbedding(pointers, options, options.shrinkage);
}

}  // namespace colmap_gcn
