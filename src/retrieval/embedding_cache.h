#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "retrieval/knn.h"
#include "retrieval/vlad.h"
#include "scene/database.h"

namespace colmap_gcn {

// Identifies an image's features for caching: a hash of its name, its
// number of descriptors and the descriptor bytes. Any change to an image's
// features changes its key; adding or removing other images does not.
uint64_t ImageFeatureKey(const std::string& name,
                         const FeatureDescriptors& descriptors);

// "<database_path>.gcn-embedding.bin".
std::string DefaultEmbeddingCachePath(const std::string& database_path);

struct EmbeddingCacheStats {
  size_t num_cached = 0;    // embeddings reused from the cache
  size_t num_computed = 0;  // embeddings computed now
};

// The embeddings of all database images, one row per image in ascending
// image id order (returned in *image_ids).
//
// With a non-empty cache_path, an image's cached embedding is reused when the
// cache was written by the same model (checksum) and the image's feature key
// still matches; everything else is recomputed and the cache rewritten. A
// missing, stale or corrupt cache only costs time; it is never an error.
EmbeddingMatrix ComputeDatabaseEmbeddings(const Database& database,
                                          const VladEmbedding& embedding,
                                          std::vector<image_t>* image_ids,
                                          const std::string& cache_path = "",
                                          int num_threads = -1,
                                          EmbeddingCacheStats* stats = nullptr);

}  // namespace colmap_gcn
