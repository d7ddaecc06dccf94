#include "pairing/knn_pairing.h"

#include <algorithm>
#include <unordered_set>

#include "util/error.h"
#include "util/option_check.h"
#include "util/option_manager.h"

namespace colmap_gcn {

void KnnPairingOptions::Check() const {
  CHECK_OPTION_GE(k, 1);
  embedding.Check();
  vlad.Check();
  CHECK_OPTION_NUM_THREADS(num_threads);
  CHECK_OPTION_GE(block_size, 1);
}

GlobalDescriptorOptions KnnPairingOptions::Descriptors() const {
  GlobalDescriptorOptions resolved;
  resolved.descriptor_path = embedding.descriptor_path;
  resolved.embedding_path = embedding_path;
  resolved.vlad = vlad;
  resolved.image_path = embedding.image_path;
  resolved.use_cache = use_cache;
  resolved.num_threads = num_threads;
  if (embedding.type == EmbeddingType::kDefault ||
      embedding.type == EmbeddingType::kImported) {
    resolved.embedding = EmbeddingType::kVlad;  // descriptor_path takes over
  } else {
    if (!embedding.descriptor_path.empty()) {
      ThrowError(
          "--GcnMatching.descriptor_path imports descriptors; it cannot be "
          "combined with --GcnMatching.embedding ",
          EnumName(EmbeddingTypeNames(), embedding.type));
    }
    resolved.embedding = embedding.type;
  }
  CnnEmbeddingOptions cnn;
  cnn.onnx_path = embedding.onnx_path;
  cnn.batch_size = embedding.onnx_batch_size;
  resolved.cnn = embedding.onnx.ApplyTo(cnn);
  return resolved;
}

std::vector<ImagePair> KnnGraphToPairs(const KnnGraph& graph,
                                       const std::vector<image_t>& image_ids) {
  THROW_CHECK(static_cast<size_t>(graph.NumImages()) == image_ids.size());
  std::vector<ImagePair> pairs;
  std::unordered_set<image_pair_t> seen;
  for (int i = 0; i < graph.NumImages(); ++i) {
    for (int n = 0; n < graph.K(); ++n) {
      const int j = graph.indices(i, n);
      if (j < 0 || j == i) continue;  // FAISS may pad with -1
      const image_t id1 = image_ids[i];
      const image_t id2 = image_ids[j];
      if (seen.insert(ImagePairToPairId(id1, id2)).second) {
        pairs.emplace_back(id1, id2);
      }
    }
  }
  return pairs;
}

KnnPairGenerator::KnnPairGenerator(const KnnPairingOptions& options,
                                   const EmbeddingMatrix& embeddings,
                                   const std::vector<image_t>& image_ids)
    : options_(options) {
  Build(embeddings, image_ids);
}

KnnPairGenerator::KnnPairGenerator(const KnnPairingOptions& options,
                                   const Database& database)
    : options_(options) {
  options_.Check();
  GlobalDescriptorOptions descriptor_options = options_.Descriptors();
  descriptor_options.num_threads = options_.num_threads;
  descriptor_options.vlad.num_threads = options_.num_threads;
  std::vector<image_t> image_ids;
  const EmbeddingMatrix embeddings =
      ComputeGlobalDescriptors(database, descriptor_options, &image_ids);
  Build(embeddings, image_ids);
}

void KnnPairGenerator::Build(const EmbeddingMatrix& embeddings,
                             const std::vector<image_t>& image_ids) {
  options_.Check();
  THROW_CHECK(static_cast<size_t>(embeddings.rows()) == image_ids.size());
  KnnOptions knn_options;
  knn_options.k = options_.k;
  knn_options.num_threads = options_.num_threads;
  knn_options.method = options_.knn_method;
  image_pairs_ =
      KnnGraphToPairs(ComputeKnn(embeddings, knn_options), image_ids);
}

void KnnPairGenerator::Reset() { pair_idx_ = 0; }

bool KnnPairGenerator::HasFinished() const {
  return pair_idx_ >= image_pairs_.size();
}

std::vector<ImagePair> KnnPairGenerator::Next() {
  return NextPairBlock(image_pairs_, options_.block_size, &pair_idx_);
}

PairGeneratorSpec<KnnPairingOptions> KnnPairGeneratorSpec() {
  PairGeneratorSpec<KnnPairingOptions> spec;
  spec.name = "knn";
  spec.add_options = [](OptionManager* manager, KnnPairingOptions* options) {
    manager->AddDefaultOption("GcnMatching.k",
                              &options->k,
                              "neighbours per image for knn | vocab_tree");
    manager->AddDefaultOption("GcnMatching.embedding_path",
                              &options->embedding_path,
                              "trained VLAD model (gcn_embedding_trainer); "
                              "empty: trained on this database");
    AddEmbeddingOptions(manager, &options->embedding);
    manager->AddDefaultOption("GcnMatching.num_threads",
                              &options->num_threads,
                              "threads for embedding and kNN (-1: all cores)");
  };
  spec.create = [](const KnnPairingOptions& options,
                   const PairGeneratorContext& context) {
    return std::make_unique<KnnPairGenerator>(options, context.database);
  };
  spec.depth = [](KnnPairingOptions* options) { return &options->k; };
  return spec;
}

}  // namespace colmap_gcn
