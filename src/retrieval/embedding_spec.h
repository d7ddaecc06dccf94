#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "retrieval/embedding.h"
#include "retrieval/knn.h"
#include "scene/database.h"

namespace colmap_gcn {

struct GlobalDescriptorOptions;
struct ModelEmbeddingOptions;

// One embedding ready to run on databases: a GCN model's (its VLAD codebook,
// CNN PCA, ...) or one built for a database without a model (knn).
class DatabaseEmbedding {
 public:
  virtual ~DatabaseEmbedding() = default;

  // One row per database image (ascending id, in *image_ids) before the
  // collection step. image_path is the folder of the database's images and
  // image_cache_path the cache of what was computed from the image files
  // ("" for none), for embeddings of the image files.
  virtual EmbeddingMatrix EmbedDatabase(
      const Database& database,
      const std::string& image_path,
      const std::string& image_cache_path,
      std::vector<image_t>* image_ids) const = 0;

  // The collection step on the rows of one collection (one database, or
  // several stacked), e.g. CNN centring and PCA; the rows as they are for
  // embeddings without one.
  virtual EmbeddingMatrix Finalize(const EmbeddingMatrix& rows) const {
    return rows;
  }
};

// What an embedding registers (COLMAP_GCN_EMBEDDINGS in embedding.h): how to
// run it from a GCN model and, for knn, without one.
struct EmbeddingSpec {
  // From a model's stored embedding (config.type names this embedding);
  // throws Error when the blob is malformed or the options do not fit it.
  std::function<std::unique_ptr<DatabaseEmbedding>(
      const GcnEmbeddingConfig& config, const ModelEmbeddingOptions& options)>
      load;

  // Without a model (knn), built from the options or trained on the
  // database itself.
  std::function<std::unique_ptr<DatabaseEmbedding>(
      const Database& database, const GlobalDescriptorOptions& options)>
      build;
};

#define COLMAP_GCN_EMBEDDING_SPEC(value, name, spec) EmbeddingSpec spec();
COLMAP_GCN_EMBEDDINGS(COLMAP_GCN_EMBEDDING_SPEC)
#undef COLMAP_GCN_EMBEDDING_SPEC

// The spec of a registered embedding; throws Error for kDefault.
const EmbeddingSpec& GetEmbeddingSpec(EmbeddingType type);

}  // namespace colmap_gcn
