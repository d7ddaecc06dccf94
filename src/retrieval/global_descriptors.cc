#include "retrieval/global_descriptors.h"

#include "retrieval/descriptor_import.h"
#include "retrieval/embedding_cache.h"
#include "retrieval/hash.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/string.h"

namespace colmap_gcn {

void GlobalDescriptorOptions::Check() const {
  vlad.Check();
  CHECK_OPTION(embedding,
               EmbeddingUsesVlad(embedding) || EmbeddingUsesCnn(embedding),
               "be vlad, onnx or vlad+onnx");
  cnn.Check();
  CHECK_OPTION_NUM_THREADS(num_threads);
}

std::string SelfTrainedModelPath(const std::string& database_path) {
  return database_path + ".gcn-vlad.bin";
}

namespace {

// Everything the self-trained model depends on.
uint64_t SelfTrainingKey(const Database& database, const VladOptions& options) {
  uint64_t key = 0x5eed;
  for (const DatabaseImage& image : database.ReadAllImages()) {
    key = HashCombine(
        key,
        ImageFeatureKey(image.name, database.ReadDescriptors(image.image_id)));
  }
  for (const double value :
       {static_cast<double>(options.num_words),
        static_cast<double>(options.dim),
        options.self_training_shrinkage,
        static_cast<double>(options.max_training_descriptors),
        static_cast<double>(options.kmeans_iterations),
        static_cast<double>(options.max_pca_images),
        static_cast<double>(options.seed)}) {
    key = HashBytes(&value, sizeof(value), key);
  }
  return key;
}

}  // namespace

VladEmbedding LoadOrTrainSelfEmbedding(const Database& database,
                                       const VladOptions& options,
                                       bool use_cache) {
  const std::string model_path = SelfTrainedModelPath(database.Path());
  const std::string key_path = model_path + ".key";
  std::string key;
  if (use_cache) {
    key = FormatChecksum(SelfTrainingKey(database, options));
    if (ExistsFile(model_path) && ExistsFile(key_path) &&
        StringTrim(ReadTextFile(key_path)) == key) {
      try {
        return VladEmbedding::Read(model_path);
      } catch (const Error&) {
        // A corrupt cache is retrained below.
      }
    }
  }
  const VladEmbedding embedding =
      TrainVladEmbedding(std::vector<const Database*>{&database},
                         options,
                         options.self_training_shrinkage);
  if (use_cache) {
    try {
      embedding.Write(model_path);
      WriteFileAtomically(key_path, key + "\n");
    } catch (const Error& error) {
      LOG(WARNING) << "self-trained VLAD model not cached: " << error.what();
    }
  }
  return embedding;
}

EmbeddingMatrix ComputeGlobalDescriptors(const Database& database,
                                         const GlobalDescriptorOptions& options,
                                         std::vector<image_t>* image_ids) {
  options.Check();
  if (!options.descriptor_path.empty()) {
    return MatchDescriptorsToImages(
        ReadGlobalDescriptors(options.descriptor_path),
        database.ReadAllImages(),
        image_ids);
  }
  EmbeddingMatrix cnn_embeddings;
  if (EmbeddingUsesCnn(options.embedding)) {
    CnnEmbeddingOptions cnn = options.cnn;
    cnn.num_threads = options.num_threads;
    const CnnNetwork network(cnn);
    cnn_embeddings =
        MakeCnnEmbeddingModel(network).Apply(ComputeDatabaseCnnDescriptors(
            database,
            network,
            options.image_path,
            options.use_cache ? DefaultCnnCachePath(database.Path()) : "",
            image_ids));
    if (!EmbeddingUsesVlad(options.embedding)) return cnn_embeddings;
  }
  const VladEmbedding embedding =
      options.embedding_path.empty()
          ? LoadOrTrainSelfEmbedding(database, options.vlad, options.use_cache)
          : VladEmbedding::Read(options.embedding_path);
  const EmbeddingMatrix vlad_embeddings = ComputeDatabaseEmbeddings(
      database,
      embedding,
      image_ids,
      options.use_cache ? DefaultEmbeddingCachePath(database.Path()) : "",
      options.num_threads);
  if (!EmbeddingUsesCnn(options.embedding)) return vlad_embeddings;
  return ConcatenateEmbeddings(vlad_embeddings, cnn_embeddings);
}

}  // namespace colmap_gcn
