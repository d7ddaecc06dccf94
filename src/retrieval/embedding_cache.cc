// Cache file ("<database>.gcn-embedding.bin"):
//   char[8] magic "CGCNEMBC", uint32 version (1), uint64 model checksum,
//   uint32 dim, uint64 num_entries, then per entry uint64 feature key and
//   float32[dim], then uint64 HashBytes of everything before.
#include "retrieval/embedding_cache.h"

#include <unordered_map>

#include "retrieval/hash.h"
#include "retrieval/keyed_row_file.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/threading.h"

namespace colmap_gcn {
namespace {

const char kMagic[8] = {'C', 'G', 'C', 'N', 'E', 'M', 'B', 'C'};
const uint32_t kVersion = 1;

// Version and model checksum: a cache of another model is not read.
std::string CacheHeader(const VladEmbedding& model) {
  const uint64_t checksum = model.Checksum();
  std::string header(reinterpret_cast<const char*>(&kVersion), 4);
  header.append(reinterpret_cast<const char*>(&checksum), 8);
  return header;
}

}  // namespace

uint64_t ImageFeatureKey(const std::string& name,
                         const FeatureDescriptors& descriptors) {
  uint64_t seed = HashString(name, 0x9ae16a3b2f90404fULL);
  seed = HashCombine(seed, static_cast<uint64_t>(descriptors.rows()));
  seed = HashCombine(seed, static_cast<uint64_t>(descriptors.cols()));
  return HashBytes(descriptors.data(), descriptors.size(), seed);
}

std::string DefaultEmbeddingCachePath(const std::string& database_path) {
  return database_path + ".gcn-embedding.bin";
}

EmbeddingMatrix ComputeDatabaseEmbeddings(const Database& database,
                                          const VladEmbedding& embedding,
                                          std::vector<image_t>* image_ids,
                                          const std::string& cache_path,
                                          int num_threads,
                                          EmbeddingCacheStats* stats) {
  THROW_CHECK(image_ids != nullptr);
  num_threads = EffectiveNumThreads(num_threads);
  const std::vector<DatabaseImage> images = database.ReadAllImages();
  const KeyedRows cache = ReadKeyedRowFile(
      cache_path, kMagic, CacheHeader(embedding), embedding.OutputDim());
  EmbeddingMatrix embeddings(images.size(), embedding.OutputDim());
  std::vector<uint64_t> keys(images.size());
  image_ids->clear();
  EmbeddingCacheStats local_stats;
  // Database reads are sequential (Database is not thread-safe); hashing and
  // embedding run in parallel on batches. Each image writes its own row.
  const size_t batch_size = 4 * static_cast<size_t>(num_threads);
  for (size_t begin = 0; begin < images.size(); begin += batch_size) {
    const size_t end = std::min(images.size(), begin + batch_size);
    std::vector<FeatureDescriptors> batch;
    for (size_t i = begin; i < end; ++i) {
      batch.push_back(database.ReadDescriptors(images[i].image_id));
    }
    std::vector<char> cached(end - begin, 0);
    ParallelFor(static_cast<int>(begin),
                static_cast<int>(end),
                num_threads,
                [&](int i) {
                  keys[i] = ImageFeatureKey(images[i].name, batch[i - begin]);
                  const auto hit = cache.find(keys[i]);
                  if (hit != cache.end()) {
                    embeddings.row(i) = hit->second;
                    cached[i - begin] = 1;
                  } else {
                    embeddings.row(i) = embedding.Embed(batch[i - begin]);
                  }
                });
    for (size_t i = begin; i < end; ++i) {
      image_ids->push_back(images[i].image_id);
      if (cached[i - begin]) {
        ++local_stats.num_cached;
      } else {
        ++local_stats.num_computed;
      }
    }
  }
  if (!cache_path.empty() &&
      (local_stats.num_computed > 0 || cache.size() != images.size())) {
    std::vector<std::pair<uint64_t, const float*>> rows;
    for (size_t i = 0; i < keys.size(); ++i) {
      rows.emplace_back(keys[i], embeddings.row(i).data());
    }
    WriteKeyedRowFile(cache_path,
                      kMagic,
                      CacheHeader(embedding),
                      embedding.OutputDim(),
                      rows,
                      "embedding cache");
  }
  if (stats != nullptr) *stats = local_stats;
  return embeddings;
}

}  // namespace colmap_gcn
