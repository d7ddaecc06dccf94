// CNN descriptors through OpenCV DNN.
//
// Cache file ("<database>.gcn-cnn-embedding.bin"):
//   char[8] "CGCNCNNC", u32 version (1), u32 dim, u64 num_entries, then per
//   entry u64 key (HashCombine(file content hash, CnnNetwork::ConfigKey()))
//   and f32[dim], then u64 HashBytes of everything before.
// Model bytes (CnnEmbeddingModel::Serialize):
//   char[8] "CGCNCNNM", u32 version (1), str network_name, u64 checksum,
//   i32 descriptor_dim, i32 max_image_size, i32 size_multiple, f64 scale,
//   f64 mean, u8 swap_rb, f64 gem_p, u8 center, i32 pca_out, i32 pca_in,
//   f32 pca mean[in], projection[out x in], eigenvalues[out], then u64
//   HashBytes of everything before; str = u64 length + bytes.
#include "retrieval/cnn_embedding.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include <opencv2/core.hpp>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "retrieval/hash.h"
#include "retrieval/keyed_row_file.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"
#include "util/threading.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

const char kCacheMagic[8] = {'C', 'G', 'C', 'N', 'C', 'N', 'N', 'C'};
const char kModelMagic[8] = {'C', 'G', 'C', 'N', 'C', 'N', 'N', 'M'};
const uint32_t kVersion = 1;

// The first line of an OpenCV exception, without its file/line prefix.
std::string OpenCvMessage(const cv::Exception& error) {
  std::string message = error.err.empty() ? error.what() : error.err;
  const size_t newline = message.find('\n');
  if (newline != std::string::npos) message.resize(newline);
  // The importer wraps the cause: "<node> parse error: OpenCV(4.6.0)
  // <file>:<line>: error: (-2:Unspecified error) <cause> in function '...'";
  // keep the node and the cause.
  const size_t wrapped = message.find(" OpenCV(");
  if (wrapped != std::string::npos && wrapped > 0) {
    std::string cause;
    const size_t code = message.find("error: (", wrapped);
    const size_t code_end =
        code == std::string::npos ? code : message.find(") ", code);
    if (code_end != std::string::npos) {
      cause = message.substr(code_end + 2);
      const size_t function = cause.find("in function");
      if (function != std::string::npos) cause.resize(function);
    }
    message = StringTrim(message.substr(0, wrapped) + " " + cause);
  }
  return StringTrim(message);
}

std::string FileName(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string ShapeString(const cv::Mat& mat) {
  std::string shape;
  for (int d = 0; d < mat.dims; ++d) {
    if (d > 0) shape += "x";
    shape += std::to_string(mat.size[d]);
  }
  return shape;
}

// OpenCV's own log lines (the ONNX importer's "[ERROR:0@...]") are off
// while loading: failures reach users as one Error line instead.
class ScopedOpenCvSilence {
 public:
  ScopedOpenCvSilence()
      : previous_(cv::utils::logging::setLogLevel(
            cv::utils::logging::LOG_LEVEL_SILENT)) {}
  ~ScopedOpenCvSilence() { cv::utils::logging::setLogLevel(previous_); }

 private:
  cv::utils::logging::LogLevel previous_;
};

// Restores OpenCV's thread count on scope exit.
class ScopedOpenCvThreads {
 public:
  explicit ScopedOpenCvThreads(int num_threads)
      : previous_(cv::getNumThreads()) {
    cv::setNumThreads(num_threads);
  }
  ~ScopedOpenCvThreads() { cv::setNumThreads(previous_); }

 private:
  int previous_;
};

class Writer {
 public:
  template <typename T>
  void Put(const T& value) {
    out_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void PutString(const std::string& value) {
    Put<uint64_t>(value.size());
    out_ += value;
  }
  void PutFloats(const float* data, size_t count) {
    out_.append(reinterpret_cast<const char*>(data), 4 * count);
  }
  std::string& Bytes() { return out_; }

 private:
  std::string out_;
};

class Reader {
 public:
  Reader(const std::string& bytes, size_t end, const std::string& source)
      : bytes_(bytes), end_(end), source_(source) {}
  template <typename T>
  T Get() {
    Need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  std::string GetString() {
    const uint64_t size = Get<uint64_t>();
    Need(size);
    std::string value = bytes_.substr(pos_, size);
    pos_ += size;
    return value;
  }
  void GetFloats(float* data, size_t count) {
    Need(4 * count);
    std::memcpy(data, bytes_.data() + pos_, 4 * count);
    pos_ += 4 * count;
  }
  size_t Position() const { return pos_; }

 private:
  void Need(uint64_t size) const {
    if (size > end_ - pos_) ThrowError(source_, " is truncated");
  }
  const std::string& bytes_;
  size_t end_;
  const std::string& source_;
  size_t pos_ = 0;
};

}  // namespace

void CnnEmbeddingOptions::Check() const {
  CHECK_OPTION_GE(size_multiple, 1);
  CHECK_OPTION_GE(max_image_size, size_multiple);
  CHECK_OPTION_GT(scale, 0.0);
  CHECK_OPTION_RANGE(mean, 0.0, 255.0);
  CHECK_OPTION_GE(gem_p, 1.0);
  CHECK_OPTION_GE(pca_dim, 0);
  CHECK_OPTION_GE(pca_shrinkage, 0.0);
  CHECK_OPTION_GE(batch_size, 1);
  CHECK_OPTION_NUM_THREADS(num_threads);
  CHECK_OPTION_GE(progress_every, 0);
}

void CnnEmbeddingOverrides::Check() const {
  CHECK_OPTION_UNSET_OR_GE(size_multiple, -1, "the model's value", 1);
  CHECK_OPTION_UNSET_OR_GE(max_image_size, -1, "the model's value", 1);
  CHECK_OPTION(
      scale, scale == -1 || scale > 0, "be -1 (the model's value) or > 0");
  CHECK_OPTION_UNSET_OR_RANGE(mean, -1, "the model's value", 0.0, 255.0);
  CHECK_OPTION_UNSET_OR_RANGE(swap_rb, -1, "the model's value", 0, 1);
  CHECK_OPTION_UNSET_OR_GE(gem_p, -1, "the model's value", 1.0);
  CHECK_OPTION_UNSET_OR_RANGE(center, -1, "the model's value", 0, 1);
}

CnnEmbeddingOptions CnnEmbeddingOverrides::ApplyTo(
    CnnEmbeddingOptions options) const {
  if (max_image_size != -1) options.max_image_size = max_image_size;
  if (size_multiple != -1) options.size_multiple = size_multiple;
  if (scale != -1) options.scale = scale;
  if (mean != -1) options.mean = mean;
  if (swap_rb != -1) options.swap_rb = swap_rb == 1;
  if (gem_p != -1) options.gem_p = gem_p;
  if (center != -1) options.center = center == 1;
  return options;
}

void CnnEmbeddingOverrides::CheckAgainst(const CnnEmbeddingOptions& model,
                                         const std::string& prefix) const {
  auto check = [&](bool set, double value, double expected, const char* name) {
    if (set && value != expected) {
      ThrowError("the GCN model was trained with ",
                 prefix,
                 name,
                 " ",
                 expected,
                 " but it is ",
                 value,
                 "; leave it unset (-1) or train a model with it");
    }
  };
  check(max_image_size != -1,
        max_image_size,
        model.max_image_size,
        "max_image_size");
  check(
      size_multiple != -1, size_multiple, model.size_multiple, "size_multiple");
  check(scale != -1, scale, model.scale, "scale");
  check(mean != -1, mean, model.mean, "mean");
  check(swap_rb != -1, swap_rb, model.swap_rb ? 1 : 0, "swap_rb");
  check(gem_p != -1, gem_p, model.gem_p, "gem_p");
  check(center != -1, center, model.center ? 1 : 0, "center");
}

void AddCnnEmbeddingOverrideOptions(OptionManager* manager,
                                    const std::string& prefix,
                                    CnnEmbeddingOverrides* overrides) {
  manager->AddDefaultOption(prefix + "max_image_size",
                            &overrides->max_image_size,
                            "CNN input long side; -1: the model's (knn: 512)");
  manager->AddDefaultOption(prefix + "size_multiple",
                            &overrides->size_multiple,
                            "CNN input sides multiple of; -1: model's (32)");
  manager->AddDefaultOption(prefix + "scale",
                            &overrides->scale,
                            "(pixel - mean) * scale; -1: model's (1/127.5)");
  manager->AddDefaultOption(prefix + "mean",
                            &overrides->mean,
                            "subtracted from pixels; -1: model's (127.5)");
  manager->AddDefaultOption(prefix + "swap_rb",
                            &overrides->swap_rb,
                            "1: RGB input, 0: BGR; -1: model's (1)");
  manager->AddDefaultOption(prefix + "gem_p",
                            &overrides->gem_p,
                            "GeM pooling exponent; -1: model's (3)");
  manager->AddDefaultOption(prefix + "center",
                            &overrides->center,
                            "1: subtract the collection mean; -1: model's (1)");
}

std::pair<int, int> CnnInputSize(int width,
                                 int height,
                                 const CnnEmbeddingOptions& options) {
  const double factor =
      static_cast<double>(options.max_image_size) / std::max(width, height);
  const int m = options.size_multiple;
  auto round = [&](int side) {
    return std::max(1, static_cast<int>(std::lround(side * factor / m))) * m;
  };
  return {round(width), round(height)};
}

uint64_t FileChecksum(const std::string& path) {
  const std::string bytes = ReadTextFile(path);
  return HashBytes(bytes.data(), bytes.size());
}

std::string FormatChecksum(uint64_t checksum) {
  char buffer[17];
  std::snprintf(buffer,
                sizeof(buffer),
                "%016llx",
                static_cast<unsigned long long>(checksum));
  return buffer;
}

struct CnnNetwork::Impl {
  std::string model_bytes;
  // One network per worker thread (cv::dnn::Net::forward mutates it).
  std::vector<cv::dnn::Net> nets;

  cv::dnn::Net Load(const std::string& source) const {
    const ScopedOpenCvSilence silence;
    try {
      cv::dnn::Net net =
          cv::dnn::readNetFromONNX(model_bytes.data(), model_bytes.size());
      if (net.empty()) {
        ThrowError("cannot read ", source, " as an ONNX network");
      }
      net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
      net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
      return net;
    } catch (const cv::Exception& error) {
      ThrowError("cannot read ",
                 source,
                 " as an ONNX network (OpenCV: ",
                 OpenCvMessage(error),
                 ")");
    }
  }
};

CnnNetwork::CnnNetwork(const CnnEmbeddingOptions& options)
    : options_(options), impl_(std::make_unique<Impl>()) {
  options_.Check();
  if (options_.onnx_path.empty()) {
    ThrowError("no ONNX network given (onnx_path is empty)");
  }
  if (!ExistsFile(options_.onnx_path)) {
    ThrowError("ONNX network not found: ", options_.onnx_path);
  }
  impl_->model_bytes = ReadTextFile(options_.onnx_path);
  checksum_ = HashBytes(impl_->model_bytes.data(), impl_->model_bytes.size());
  const int num_threads = EffectiveNumThreads(options_.num_threads);
  for (int i = 0; i < num_threads; ++i) {
    impl_->nets.push_back(impl_->Load(options_.onnx_path));
  }
  // The output's shape, from a small input (two strides per side).
  const int side = 2 * options_.size_multiple;
  const cv::Mat probe(side, side, CV_8UC3, cv::Scalar(127, 127, 127));
  cv::Mat output;
  try {
    const ScopedOpenCvSilence silence;
    const ScopedOpenCvThreads single(1);
    impl_->nets[0].setInput(cv::dnn::blobFromImage(probe, options_.scale));
    output = impl_->nets[0].forward();
  } catch (const cv::Exception& error) {
    ThrowError(options_.onnx_path,
               " fails on a ",
               side,
               "x",
               side,
               " input (OpenCV: ",
               OpenCvMessage(error),
               ")");
  }
  const bool feature_map = output.dims == 4 && output.size[0] == 1;
  const bool vector = output.dims == 2 && output.size[0] == 1;
  if (!feature_map && !vector) {
    ThrowError(options_.onnx_path,
               " outputs ",
               ShapeString(output),
               "; expected a feature map 1xCxHxW or a vector 1xC");
  }
  descriptor_dim_ = output.size[1];
}

CnnNetwork::~CnnNetwork() = default;

uint64_t CnnNetwork::ConfigKey() const {
  uint64_t key = HashCombine(0xc0ffee, checksum_);
  for (const double value : {static_cast<double>(options_.max_image_size),
                             static_cast<double>(options_.size_multiple),
                             options_.scale,
                             options_.mean,
                             options_.swap_rb ? 1.0 : 0.0,
                             options_.gem_p}) {
    key = HashBytes(&value, sizeof(value), key);
  }
  return key;
}

namespace {

// GeM over h x w per channel (double accumulation in a fixed order), or the
// vector itself; then L2.
Eigen::RowVectorXf PoolOutput(const cv::Mat& output, int index, double p) {
  const int channels = output.size[1];
  Eigen::RowVectorXf descriptor(channels);
  const float* data = output.ptr<float>(index);
  const size_t area = output.dims == 4
                          ? static_cast<size_t>(output.size[2]) * output.size[3]
                          : 1;
  for (int c = 0; c < channels; ++c) {
    const float* channel = data + c * area;
    if (area == 1) {
      descriptor(c) = channel[0];
      continue;
    }
    double sum = 0;
    for (size_t i = 0; i < area; ++i) {
      const double x = std::max(static_cast<double>(channel[i]), 1e-6);
      sum += p == 1.0 ? x : (p == 3.0 ? x * x * x : std::pow(x, p));
    }
    const double mean = sum / area;
    descriptor(c) =
        static_cast<float>(p == 1.0 ? mean : std::pow(mean, 1.0 / p));
  }
  const float norm = descriptor.norm();
  if (norm > 0) descriptor /= norm;
  return descriptor;
}

cv::Mat DecodeImage(const std::string& bytes, const std::string& source) {
  cv::Mat image;
  try {
    const cv::Mat buffer(1,
                         static_cast<int>(bytes.size()),
                         CV_8UC1,
                         const_cast<char*>(bytes.data()));
    image = cv::imdecode(buffer, cv::IMREAD_COLOR);
  } catch (const cv::Exception& error) {
    ThrowError("cannot decode image ", source, " (", OpenCvMessage(error), ")");
  }
  if (image.empty()) {
    ThrowError("cannot decode image ", source);
  }
  return image;
}

}  // namespace

Eigen::RowVectorXf CnnNetwork::DescribeEncoded(
    const std::string& bytes, const std::string& source) const {
  return DescribeEncodedBatch({{bytes, source}}).row(0);
}

FloatMatrix CnnNetwork::DescribeEncodedBatch(
    const std::vector<std::pair<std::string, std::string>>& items) const {
  FloatMatrix result(items.size(), descriptor_dim_);
  const int batch = options_.batch_size;
  const int num_chunks =
      static_cast<int>((items.size() + batch - 1) / static_cast<size_t>(batch));
  // Each worker's network runs single-threaded, so an image's result never
  // depends on how many workers there are.
  const ScopedOpenCvThreads single(1);
  ParallelFor(
      0,
      num_chunks,
      static_cast<int>(impl_->nets.size()),
      [&](int chunk, int thread) {
        const size_t begin = static_cast<size_t>(chunk) * batch;
        const size_t end = std::min(items.size(), begin + batch);
        std::vector<cv::Mat> inputs;
        for (size_t i = begin; i < end; ++i) {
          const cv::Mat image = DecodeImage(items[i].first, items[i].second);
          const auto [width, height] =
              CnnInputSize(image.cols, image.rows, options_);
          cv::Mat resized;
          cv::resize(image,
                     resized,
                     cv::Size(width, height),
                     0,
                     0,
                     width < image.cols ? cv::INTER_AREA : cv::INTER_LINEAR);
          inputs.push_back(resized);
        }
        cv::dnn::Net& net = impl_->nets[thread];
        // Runs of equal size share one forward pass.
        for (size_t first = 0; first < inputs.size();) {
          size_t last = first + 1;
          while (last < inputs.size() &&
                 inputs[last].size() == inputs[first].size()) {
            ++last;
          }
          const std::vector<cv::Mat> run(inputs.begin() + first,
                                         inputs.begin() + last);
          cv::Mat output;
          try {
            net.setInput(cv::dnn::blobFromImages(
                run,
                options_.scale,
                cv::Size(),
                cv::Scalar(options_.mean, options_.mean, options_.mean),
                options_.swap_rb,
                /*crop=*/false));
            output = net.forward();
          } catch (const cv::Exception& error) {
            ThrowError(options_.onnx_path,
                       " fails on image ",
                       items[begin + first].second,
                       " (OpenCV: ",
                       OpenCvMessage(error),
                       ")");
          }
          if (output.size[0] != static_cast<int>(run.size()) ||
              output.size[1] != descriptor_dim_) {
            ThrowError(options_.onnx_path,
                       " outputs ",
                       ShapeString(output),
                       " for a batch of ",
                       run.size(),
                       "; expected ",
                       run.size(),
                       "x",
                       descriptor_dim_,
                       "x...");
          }
          for (size_t i = first; i < last; ++i) {
            result.row(begin + i) =
                PoolOutput(output, static_cast<int>(i - first), options_.gem_p);
          }
          first = last;
        }
      });
  return result;
}

std::string DefaultCnnCachePath(const std::string& database_path) {
  return database_path + ".gcn-cnn-embedding.bin";
}

namespace {

std::string CnnCacheHeader() {
  return std::string(reinterpret_cast<const char*>(&kVersion), 4);
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
    std::vector<std::pair<uint64_t, const float*>> rows;
    for (size_t i = 0; i < done; ++i) {
      rows.emplace_back(keys[i], descriptors.row(i).data());
    }
    // Entries of images not reached yet survive interim writes.
    if (done < images.size()) {
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

EmbeddingMatrix CnnEmbeddingModel::Apply(const FloatMatrix& raw) const {
  THROW_CHECK(raw.cols() == descriptor_dim);
  FloatMatrix x = raw;
  auto normalise = [](FloatMatrix* rows) {
    for (Eigen::Index i = 0; i < rows->rows(); ++i) {
      const float norm = rows->row(i).norm();
      if (norm > 0) rows->row(i) /= norm;
    }
  };
  if (options.center && x.rows() > 0) {
    const Eigen::RowVectorXf mean = x.colwise().mean();
    x.rowwise() -= mean;
    if (HasPca()) normalise(&x);
  }
  if (HasPca()) x = pca.Apply(x);
  normalise(&x);
  return x;
}

void CnnEmbeddingModel::CheckNetwork(const CnnNetwork& network,
                                     const std::string& flag) const {
  if (network.NetworkChecksum() != network_checksum) {
    ThrowError("the model was trained on ",
               network_name,
               " (checksum ",
               FormatChecksum(network_checksum),
               ") but ",
               flag,
               " is ",
               network.Options().onnx_path,
               " (checksum ",
               FormatChecksum(network.NetworkChecksum()),
               ")");
  }
  if (network.DescriptorDim() != descriptor_dim) {
    ThrowError("the model expects ",
               descriptor_dim,
               "-dimensional descriptors from ",
               network_name,
               " but the network gives ",
               network.DescriptorDim());
  }
}

std::string CnnEmbeddingModel::Serialize() const {
  Writer writer;
  writer.Bytes().append(kModelMagic, 8);
  writer.Put<uint32_t>(kVersion);
  writer.PutString(network_name);
  writer.Put<uint64_t>(network_checksum);
  writer.Put<int32_t>(descriptor_dim);
  writer.Put<int32_t>(options.max_image_size);
  writer.Put<int32_t>(options.size_multiple);
  writer.Put<double>(options.scale);
  writer.Put<double>(options.mean);
  writer.Put<uint8_t>(options.swap_rb ? 1 : 0);
  writer.Put<double>(options.gem_p);
  writer.Put<uint8_t>(options.center ? 1 : 0);
  writer.Put<int32_t>(pca.OutputDim());
  writer.Put<int32_t>(HasPca() ? pca.InputDim() : 0);
  if (HasPca()) {
    writer.PutFloats(pca.mean.data(), pca.mean.size());
    writer.PutFloats(pca.projection.data(), pca.projection.size());
    writer.PutFloats(pca.eigenvalues.data(), pca.eigenvalues.size());
  }
  const uint64_t hash = HashBytes(writer.Bytes().data(), writer.Bytes().size());
  writer.Put<uint64_t>(hash);
  return writer.Bytes();
}

CnnEmbeddingModel CnnEmbeddingModel::Deserialize(const std::string& bytes,
                                                 const std::string& source) {
  if (bytes.size() < 8 + 4 + 8 ||
      std::memcmp(bytes.data(), kModelMagic, 8) != 0) {
    ThrowError(source, " is not a CNN embedding configuration (bad magic)");
  }
  uint64_t stored_hash;
  std::memcpy(&stored_hash, bytes.data() + bytes.size() - 8, 8);
  if (HashBytes(bytes.data(), bytes.size() - 8) != stored_hash) {
    ThrowError(source, " is corrupt (checksum mismatch)");
  }
  Reader reader(bytes, bytes.size() - 8, source);
  reader.Get<uint64_t>();  // magic
  const uint32_t version = reader.Get<uint32_t>();
  if (version != kVersion) {
    ThrowError(source, " has unsupported version ", version);
  }
  CnnEmbeddingModel model;
  model.network_name = reader.GetString();
  model.network_checksum = reader.Get<uint64_t>();
  model.descriptor_dim = reader.Get<int32_t>();
  model.options.max_image_size = reader.Get<int32_t>();
  model.options.size_multiple = reader.Get<int32_t>();
  model.options.scale = reader.Get<double>();
  model.options.mean = reader.Get<double>();
  model.options.swap_rb = reader.Get<uint8_t>() != 0;
  model.options.gem_p = reader.Get<double>();
  model.options.center = reader.Get<uint8_t>() != 0;
  const int pca_out = reader.Get<int32_t>();
  const int pca_in = reader.Get<int32_t>();
  if (model.descriptor_dim < 1 || pca_out < 0 ||
      (pca_out > 0 && pca_in != model.descriptor_dim) ||
      (pca_out == 0 && pca_in != 0)) {
    ThrowError(source, " is malformed (dimensions)");
  }
  model.options.pca_dim = pca_out;
  if (pca_out > 0) {
    model.pca.mean.resize(pca_in);
    model.pca.projection.resize(pca_out, pca_in);
    model.pca.eigenvalues.resize(pca_out);
    reader.GetFloats(model.pca.mean.data(), pca_in);
    reader.GetFloats(model.pca.projection.data(),
                     static_cast<size_t>(pca_out) * pca_in);
    reader.GetFloats(model.pca.eigenvalues.data(), pca_out);
  }
  if (reader.Position() != bytes.size() - 8) {
    ThrowError(source, " has trailing bytes");
  }
  return model;
}

CnnEmbeddingModel MakeCnnEmbeddingModel(const CnnNetwork& network) {
  CnnEmbeddingModel model;
  model.network_name = FileName(network.Options().onnx_path);
  model.network_checksum = network.NetworkChecksum();
  model.descriptor_dim = network.DescriptorDim();
  model.options = network.Options();
  model.options.onnx_path = "";
  model.options.pca_dim = 0;
  return model;
}

CnnEmbeddingModel TrainCnnEmbeddingModel(
    const CnnNetwork& network, const std::vector<FloatMatrix>& collections) {
  CnnEmbeddingModel model = MakeCnnEmbeddingModel(network);
  const CnnEmbeddingOptions& options = network.Options();
  if (options.pca_dim == 0) return model;
  Eigen::Index num_rows = 0;
  for (const auto& collection : collections) num_rows += collection.rows();
  FloatMatrix samples(num_rows, model.descriptor_dim);
  Eigen::Index offset = 0;
  for (const auto& collection : collections) {
    // Centred (and normalised) per collection, as Apply will at test time.
    samples.middleRows(offset, collection.rows()) = model.Apply(collection);
    offset += collection.rows();
  }
  PcaOptions pca_options;
  pca_options.dim = options.pca_dim;
  pca_options.shrinkage = options.pca_shrinkage;
  model.pca = TrainPcaWhitening(samples, pca_options);
  model.options.pca_dim = model.pca.OutputDim();
  model.options.pca_shrinkage = options.pca_shrinkage;
  return model;
}

EmbeddingMatrix ConcatenateEmbeddings(const EmbeddingMatrix& a,
                                      const EmbeddingMatrix& b) {
  THROW_CHECK(a.rows() == b.rows());
  EmbeddingMatrix result(a.rows(), a.cols() + b.cols());
  const float half = static_cast<float>(1.0 / std::sqrt(2.0));
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const float norm_a = a.row(i).norm();
    const float norm_b = b.row(i).norm();
    result.row(i).head(a.cols()) =
        norm_a > 0 ? Eigen::RowVectorXf(a.row(i) * (half / norm_a))
                   : Eigen::RowVectorXf::Zero(a.cols());
    result.row(i).tail(b.cols()) =
        norm_b > 0 ? Eigen::RowVectorXf(b.row(i) * (half / norm_b))
                   : Eigen::RowVectorXf::Zero(b.cols());
  }
  return result;
}

}  // namespace colmap_gcn
