// Cache file ("<database>.gcn-embedding.bin"):
//   char[8] magic "CGCNEMBC", uint32 version (1), uint64 model checksum,
//   uint32 dim, uint64 num_entries, then per entry uint64 feature key and
//   float32[dim], then uint64 HashBytes of everything before.
#include "retrieval/embedding_cache.h"

#include <cstring>
#include <unordered_map>

#include "retrieval/hash.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/threading.h"

namespace colmap_gcn {
namespace {

const char kMagic[8] = {'C', 'G', 'C', 'N', 'E', 'M', 'B', 'C'};
const uint32_t kVersion = 1;

typedef std::unordered_map<uint64_t, Eigen::RowVectorXf> CacheEntries;

// Entries of a valid cache for this model, or none.
CacheEntries ReadCache(const std::string& path, const VladEmbedding& model) {
  CacheEntries entries;
  if (path.empty() || !ExistsFile(path)) return entries;
  std::string contents;
  try {
    contents = ReadTextFile(path);
  } catch (const Error&) {
    return entries;
  }
  const size_t header_size = 8 + 4 + 8 + 4 + 8;
  if (contents.size() < header_size + 8 ||
      std::memcmp(contents.data(), kMagic, 8) != 0) {
    return entries;
  }
  uint32_t version, dim;
  uint64_t checksum, num_entries, stored_hash;
  std::memcpy(&version, contents.data() + 8, 4);
  std::memcpy(&checksum, contents.data() + 12, 8);
  std::memcpy(&dim, contents.data() + 20, 4);
  std::memcpy(&num_entries, contents.data() + 24, 8);
  const size_t entry_size = 8 + 4 * static_cast<size_t>(dim);
  if (version != kVersion || checksum != model.Checksum() ||
      dim != static_cast<uint32_t>(model.OutputDim()) ||
      num_entries > contents.size() / entry_size ||
      contents.size() != header_size + num_entries * entry_size + 8) {
    return entries;
  }
  std::memcpy(&stored_hash, contents.data() + contents.size() - 8, 8);
  if (HashBytes(contents.data(), contents.size() - 8) != stored_hash) {
    return entries;
  }
  const char* data = contents.data() + header_size;
  for (uint64_t i = 0; i < num_entries; ++i, data += entry_size) {
    uint64_t key;
    std::memcpy(&key, data, 8);
    Eigen::RowVectorXf row(dim);
    std::memcpy(row.data(), data + 8, 4 * static_cast<size_t>(dim));
    entries[key] = std::move(row);
  }
  return entries;
}

void WriteCache(const std::string& path,
                const VladEmbedding& model,
                const std::vector<uint64_t>& keys,
                const EmbeddingMatrix& embeddings) {
  std::string out(kMagic, 8);
  const uint64_t checksum = model.Checksum();
  const uint32_t dim = static_cast<uint32_t>(embeddings.cols());
  const uint64_t num_entries = keys.size();
  out.append(reinterpret_cast<const char*>(&kVersion), 4);
  out.append(reinterpret_cast<const char*>(&checksum), 8);
  out.append(reinterpret_cast<const char*>(&dim), 4);
  out.append(reinterpret_cast<const char*>(&num_entries), 8);
  for (size_t i = 0; i < keys.size(); ++i) {
    out.append(reinterpret_cast<const char*>(&keys[i]), 8);
    out.append(reinterpret_cast<const char*>(embeddings.row(i).data()),
               4 * static_cast<size_t>(dim));
  }
  const uint64_t hash = HashBytes(out.data(), out.size());
  out.append(reinterpret_cast<const char*>(&hash), 8);
  try {
    WriteFileAtomically(path, out);
  } catch (const Error& error) {
    // A read-only folder only loses the cache.
    LOG(WARNING) << "embedding cache not written: " << error.what();
  }
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
  const CacheEntries cache = ReadCache(cache_path, embedding);
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
    WriteCache(cache_path, embedding, keys, embeddings);
  }
  if (stats != nullptr) *stats = local_stats;
  return embeddings;
}

}  // namespace colmap_gcn
