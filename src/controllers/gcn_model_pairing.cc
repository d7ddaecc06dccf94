#include "controllers/gcn_model_pairing.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "retrieval/descriptor_import.h"
#include "retrieval/embedding_cache.h"
#include "retrieval/vlad.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"
#include "util/string.h"

namespace colmap_gcn {

void GcnModelPairingOptions::Check() const {
  CHECK_OPTION_UNSET_OR_GE(k1, -1, "the model's value", 1);
  CHECK_OPTION_UNSET_OR_GE(k2, -1, "the model's value", 1);
  CHECK_OPTION_UNSET_OR_GE(u, -1, "the model's value", 1);
  CHECK_OPTION_UNSET_OR_RANGE(threshold, -1, "the model's value", 0.0, 1.0);
  CHECK_OPTION_GE(min_pairs_per_image, 0);
  CHECK_OPTION_NUM_THREADS(num_threads);
}

std::string DefaultGcnModelPath() {
  const char* env = std::getenv("COLMAP_GCN_MODEL");
  if (env != nullptr && *env != '\0') {
    return env;
  }
  std::error_code ec;
  const std::filesystem::path exe =
      std::filesystem::canonical("/proc/self/exe", ec);
  const std::string kName = "default.gcnmodel";
  if (!ec) {
    const std::string installed =
        (exe.parent_path().parent_path() / "share" / "colmap-gcn" / kName)
            .string();
    if (ExistsFile(installed)) return installed;
  }
  const std::string source_tree =
      JoinPaths(COLMAP_GCN_SOURCE_DIR, "colmap_gcn/models/" + kName);
  return ExistsFile(source_tree) ? source_tree : "";
}

EmbeddingMatrix ComputeModelEmbeddings(const GcnModel& model,
                                       const Database& database,
                                       const std::string& descriptor_path,
                                       int num_threads,
                                       std::vector<image_t>* image_ids) {
  const GcnEmbeddingConfig& config = model.embedding;
  EmbeddingMatrix embeddings;
  if (config.type == "vlad") {
    if (!descriptor_path.empty()) {
      ThrowError(
          "the GCN model was trained on its own VLAD embedding; imported "
          "descriptors (--GcnMatching.descriptor_path) need a model trained "
          "on them");
    }
    const VladEmbedding vlad =
        VladEmbedding::Deserialize(config.blob, "the GCN model's embedding");
    embeddings =
        ComputeDatabaseEmbeddings(database,
                                  vlad,
                                  image_ids,
                                  DefaultEmbeddingCachePath(database.Path()),
                                  num_threads);
  } else if (StringStartsWith(config.type, "imported")) {
    if (descriptor_path.empty()) {
      ThrowError("the GCN model was trained on imported descriptors (",
                 config.type,
                 "); pass them with --GcnMatching.descriptor_path");
    }
    embeddings =
        MatchDescriptorsToImages(ReadGlobalDescriptors(descriptor_path),
                                 database.ReadAllImages(),
                                 image_ids);
  } else {
    ThrowError(
        "the GCN model has an unknown embedding type \"", config.type, "\"");
  }
  model.CheckEmbeddingDimension(static_cast<int>(embeddings.cols()));
  return embeddings;
}

}  // namespace colmap_gcn
