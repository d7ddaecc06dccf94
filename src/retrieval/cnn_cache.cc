// The CNN descriptor cache of a database's images.
//
// Cache file ("<database>.gcn-cnn-embedding.bin"):
//   char[8] "CGCNCNNC", u32 version (1), u32 dim, u64 num_entries, then per
//   entry u64 key (HashCombine(file content hash, CnnNetwork::ConfigKey()))
//   and f32[dim], then u64 HashBytes of everything before.
#include "retrieval/cnn_embedding.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "retrieval/hash.h"
#include "retrieval/keyed_row_file.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/threading.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

const char kCacheMagic[8] = {'C', 'G', 'C', 'N', 'C', 'N', 'N', 'C'};
const uint32_t kVersion = 1;

}  // namespace

std::string DefaultCnnCachePath(const std::string& database_path) {
  return database_path + ".gcn-cnn-embedding.bin";
}

namespace {

std::string CnnCacheHeader() {
  return std::string(reinterpret_cast<const char*>(&kVersion), 4);
}

// Writes the rows of images [0, done) and, in interim writes (done < all),
// the entries of the old cache not reached yet.
void WriteCnnCache(const std::string& cache_path,
                   const int dim,
                   const std::vector<uint64_t>& keys,
                   const FloatMatrix& descriptors,
                   const size_t done,
                   const KeyedRows& cache) {
  std::vector<std::pair<uint64_t, const float*>> rows;
  for (size_t i = 0; i < done; ++i) {
    rows.emplace_back(keys[i], descriptors.row(i).data());
  }
  if (done < keys.size()) {
    std::unordered_map<uint64_t, bool> present;
    for (size_t i = 0; i < done; ++i) present[keys[i]] = true;
    for (const auto& [key, row] : cache) {
      if (!present.count(key)) rows.emplace_back(key, row.data());
    }
  }
  WriteKeyedRowFile(cache_path,
                    kCacheMagic,
                    CnnCacheHeader(),
                    dim,
                    rows,
                    "CNN embedding cache");
}

}  // namespace

FloatMatrix ComputeDatabaseCnnDescriptors(const Database& database,
                                          const CnnNetwork& network,
                                          const std::string& image_path,
                                          const std::string& cache_path,
                                          std::vector<image_t>* image_ids,
                                          EmbeddingCacheStats* stats) {
  THROW_CHECK(image_ids != nullptr);
  if (image_path.empty()) {
    ThrowError(
        "the CNN embedding reads the image files: name their folder (the "
        "one given to feature_extractor) with --GcnMatching.image_path");
  }
  if (!ExistsDir(image_path)) {
    ThrowError("image folder not found: ", image_path);
  }
  const std::vector<DatabaseImage> images = database.ReadAllImages();
  const int dim = network.DescriptorDim();
  const uint64_t config_key = network.ConfigKey();
  const KeyedRows cache =
      ReadKeyedRowFile(cache_path, kCacheMagic, CnnCacheHeader(), dim);
  FloatMatrix descriptors(images.size(), dim);
  std::vector<uint64_t> keys(images.size());
  image_ids->clear();
  for (const auto& image : images) image_ids->push_back(image.image_id);
  EmbeddingCacheStats local_stats;
  const CnnEmbeddingOptions& options = network.Options();
  const int num_threads = EffectiveNumThreads(options.num_threads);
  const Timer timer;
  double last_write = 0;
  std::optional<ProgressLogger> progress;
  if (options.progress_every > 0) {
    progress.emplace(images.size(), "CNN embedding", "images");
  }
  // Chunks: files are read and hashed in parallel, misses embedded, and
  // every ~30 s the cache is rewritten so an interrupted run resumes.
  const size_t chunk_size =
      static_cast<size_t>(std::max(8, 4 * num_threads * options.batch_size));
  auto write_cache = [&](size_t done) {
    WriteCnnCache(cache_path, dim, keys, descriptors, done, cache);
  };
  // Images [0, done) have their descriptors.
  size_t done = 0;
  try {
    for (size_t begin = 0; begin < images.size(); begin += chunk_size) {
      const size_t end = std::min(images.size(), begin + chunk_size);
      std::vector<std::string> bytes(end - begin);
      std::vector<char> cached(end - begin, 0);
      ParallelFor(static_cast<int>(begin),
                  static_cast<int>(end),
                  num_threads,
                  [&](int i) {
                    const std::string path =
                        JoinPaths(image_path, images[i].name);
                    if (!ExistsFile(path)) {
                      ThrowError("cannot read image ",
                                 images[i].name,
                                 ": ",
                                 path,
                                 " does not exist");
                    }
                    std::string& data = bytes[i - begin];
                    data = ReadTextFile(path);
                    keys[i] = HashCombine(HashBytes(data.data(), data.size()),
                                          config_key);
                    const auto hit = cache.find(keys[i]);
                    if (hit != cache.end()) {
                      descriptors.row(i) = hit->second;
                      cached[i - begin] = 1;
                    }
                  });
      std::vector<std::pair<std::string, std::string>> misses;
      std::vector<size_t> miss_rows;
      for (size_t i = begin; i < end; ++i) {
        if (cached[i - begin]) {
          ++local_stats.num_cached;
        } else {
          misses.emplace_back(std::move(bytes[i - begin]),
                              JoinPaths(image_path, images[i].name));
          miss_rows.push_back(i);
        }
      }
      if (!misses.empty()) {
        const FloatMatrix computed = network.DescribeEncodedBatch(misses);
        for (size_t m = 0; m < miss_rows.size(); ++m) {
          descriptors.row(miss_rows[m]) = computed.row(m);
        }
        local_stats.num_computed += misses.size();
      }
      if (progress) progress->Update(end);
      if (!cache_path.empty() && local_stats.num_computed > 0 &&
          end < images.size() && timer.ElapsedSeconds() - last_write > 30) {
        write_cache(end);
        last_write = timer.ElapsedSeconds();
      }
      done = end;
    }
  } catch (...) {
    // What was computed before an unreadable image (or an interruption that
    // throws) is kept for the next run.
    if (!cache_path.empty() && local_stats.num_computed > 0 && done > 0) {
      write_cache(done);
    }
    throw;
  }
  // Rewritten when something was computed or stale entries are dropped
  // (images with identical files share one entry).
  const size_t num_keys =
      std::unordered_set<uint64_t>(keys.begin(), keys.end()).size();
  if (!cache_path.empty() &&
      (local_stats.num_computed > 0 || cache.size() != num_keys)) {
    write_cache(images.size());
  }
  if (stats != nullptr) *stats = local_stats;
  return descriptors;
}

}  // namespace colmap_gcn
