#pragma once

#include <string>
#include <vector>

#include "pairing/pair_generator_spec.h"
#include "pairing/pairing.h"
#include "retrieval/embedding.h"
#include "retrieval/global_descriptors.h"
#include "retrieval/knn.h"
#include "scene/database.h"

namespace colmap_gcn {

struct KnnPairingOptions {
  // Neighbours retrieved per image (capped at N - 1): the paper's "CNN
  // retrieval with fixed k" baseline.
  int k = 25;

  // The embedding flags: type default is vlad, or the imported descriptors
  // when descriptor_path is set; vlad | onnx | vlad+onnx choose a computed
  // one (not with descriptor_path); imported needs descriptor_path. Unset
  // onnx_* keep MobileNetV2's preprocessing (CnnEmbeddingOptions).
  EmbeddingOptions embedding;

  // A VLAD model trained by `colmap gcn_embedding_trainer`. Empty: train one
  // on the target database itself (cached as "<database>.gcn-vlad.bin").
  std::string embedding_path = "";

  // Training options of the self-trained VLAD model.
  VladOptions vlad;

  // Keep the embeddings (and the self-trained model) beside the database.
  bool use_cache = true;

  // See KnnOptions::method.
  KnnMethod knn_method = KnnMethod::kExact;

  // Threads for embedding and kNN; -1 uses all cores.
  int num_threads = -1;

  // Number of image pairs in one block.
  int block_size = 1225;

  // Throws OptionError naming the first invalid field.
  void Check() const;

  // Where the descriptors come from, resolved from the fields above. Throws
  // Error when imported descriptors are combined with a computed embedding.
  GlobalDescriptorOptions Descriptors() const;
};

// The unordered pairs {i, j} for j among the k nearest neighbours of i, each
// once, in order of first appearance (queries in row order, neighbours by
// rank), oriented (query, neighbour) as first seen.
std::vector<ImagePair> KnnGraphToPairs(const KnnGraph& graph,
                                       const std::vector<image_t>& image_ids);

// Top-k retrieval on global descriptors. All the work happens in the
// constructor; Next() hands out blocks.
class KnnPairGenerator : public PairGenerator {
 public:
  using PairOptions = KnnPairingOptions;

  // From precomputed embeddings (row i belongs to image_ids[i]).
  KnnPairGenerator(const KnnPairingOptions& options,
                   const EmbeddingMatrix& embeddings,
                   const std::vector<image_t>& image_ids);
  // Computes the global descriptors of the database first.
  KnnPairGenerator(const KnnPairingOptions& options, const Database& database);

  void Reset() override;
  bool HasFinished() const override;
  std::vector<ImagePair> Next() override;

 private:
  void Build(const EmbeddingMatrix& embeddings,
             const std::vector<image_t>& image_ids);

  const KnnPairingOptions options_;
  std::vector<ImagePair> image_pairs_;
  size_t pair_idx_ = 0;
};

// --GcnMatching.pairing knn (--GcnMatching.k, embedding_path, the embedding
// flags (AddEmbeddingOptions), num_threads).
PairGeneratorSpec<KnnPairingOptions> KnnPairGeneratorSpec();

}  // namespace colmap_gcn
