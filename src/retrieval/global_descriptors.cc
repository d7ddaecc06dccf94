#include "retrieval/global_descriptors.h"

#include "retrieval/embedding_cache.h"
#include "retrieval/embedding_spec.h"
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
               embedding != EmbeddingType::kDefault &&
                   embedding != EmbeddingType::kImported,
               "be an embedding computed from the database (not default or "
               "imported: descriptor_path imports)");
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
  const EmbeddingType type = options.descriptor_path.empty()
                                 ? options.embedding
                                 : EmbeddingType::kImported;
  const std::unique_ptr<DatabaseEmbedding> embedding =
      GetEmbeddingSpec(type).build(database, options);
  return embedding->Finalize(embedding->EmbedDatabase(
      database,
      options.image_path,
      options.use_cache ? DefaultCnnCachePath(database.Path()) : "",
      image_ids));
}

}  // namespace colmap_gcn
