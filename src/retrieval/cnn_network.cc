// CnnNetwork: the OpenCV DNN runtime (loading and checking the ONNX
// network, preprocessing, batched forward passes, GeM pooling).
#include "retrieval/cnn_embedding.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <opencv2/core.hpp>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "retrieval/hash.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/string.h"
#include "util/threading.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

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

}  // namespace

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

}  // namespace colmap_gcn
