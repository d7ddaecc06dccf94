#include "retrieval/cnn_embedding.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "retrieval_test_utils.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"

namespace colmap_gcn {
namespace {

// ../shared/models/mobilenet_v2_imagenet_features.onnx, or "" (tests that
// need it skip).
std::string SharedNetworkPath() {
  const std::string datasets = test::SharedDatasetsDir();
  if (datasets.empty()) return "";
  const std::string path =
      JoinPaths(datasets, "../models/mobilenet_v2_imagenet_features.onnx");
  return ExistsFile(path) ? path : "";
}

#define SKIP_WITHOUT_NETWORK()                                         \
  if (SharedNetworkPath().empty()) {                                   \
    GTEST_SKIP() << "../shared/models/mobilenet_v2_imagenet_features." \
                    "onnx not found";                                  \
  }

void WriteFile(const std::string& path, const std::string& contents) {
  std::ofstream file(path, std::ios::binary);
  file << contents;
}

// A hand-encoded ONNX model (protobuf wire format, opset 11) with input x
// (N x 3 x H x W): Relu (a 3-channel "feature map"), or Relu then Reshape to
// N x 3 x (H W) (a 3-D output, which no descriptor is).
class Protobuf {
 public:
  Protobuf& Varint(int field, uint64_t value) {
    Key(field, 0);
    Raw(value);
    return *this;
  }
  Protobuf& Bytes(int field, const std::string& bytes) {
    Key(field, 2);
    Raw(bytes.size());
    out_ += bytes;
    return *this;
  }
  Protobuf& Message(int field, const Protobuf& message) {
    return Bytes(field, message.out_);
  }
  const std::string& Str() const { return out_; }

 private:
  void Key(int field, int wire_type) { Raw((field << 3) | wire_type); }
  void Raw(uint64_t value) {
    while (value >= 0x80) {
      out_ += static_cast<char>((value & 0x7f) | 0x80);
      value >>= 7;
    }
    out_ += static_cast<char>(value);
  }
  std::string out_;
};

std::string TinyOnnx(bool reshape) {
  Protobuf shape;
  for (const char* dim : {"n", "c", "h", "w"}) {
    shape.Message(1, Protobuf().Bytes(2, dim));  // dim { dim_param }
  }
  const Protobuf input_type = Protobuf().Message(
      1, Protobuf().Varint(1, 1).Message(2, shape));  // float tensor
  Protobuf graph;
  graph.Message(
      1,
      Protobuf().Bytes(1, "x").Bytes(2, reshape ? "r" : "y").Bytes(4, "Relu"));
  if (reshape) {
    Protobuf values;
    for (const int64_t v : {int64_t{1}, int64_t{3}, int64_t{-1}}) {
      values.Varint(7, static_cast<uint64_t>(v));  // int64_data
    }
    std::string tensor = Protobuf().Varint(1, 3).Varint(2, 7).Str();
    tensor += values.Str();
    tensor += Protobuf().Bytes(8, "s").Str();  // name
    graph.Message(1,
                  Protobuf().Bytes(1, "r").Bytes(1, "s").Bytes(2, "y").Bytes(
                      4, "Reshape"));
    graph.Bytes(5, tensor);  // initializer
  }
  graph.Bytes(2, "tiny");
  graph.Message(11, Protobuf().Bytes(1, "x").Message(2, input_type));
  Protobuf output_shape;
  for (const char* dim : reshape
                             ? std::vector<const char*>{"n", "c", "hw"}
                             : std::vector<const char*>{"n", "c", "h", "w"}) {
    output_shape.Message(1, Protobuf().Bytes(2, dim));
  }
  const Protobuf output_type =
      Protobuf().Message(1, Protobuf().Varint(1, 1).Message(2, output_shape));
  graph.Message(12, Protobuf().Bytes(1, "y").Message(2, output_type));
  return Protobuf()
      .Varint(1, 6)                          // ir_version
      .Message(8, Protobuf().Varint(2, 11))  // opset_import { version }
      .Message(7, graph)
      .Str();
}

TEST(CnnEmbedding, TinyNetworkGivesPooledUnitVectors) {
  const TemporaryDirectory dir;
  CnnEmbeddingOptions options;
  options.onnx_path = JoinPaths(dir.Path(), "relu.onnx");
  options.progress_every = 0;
  WriteFile(options.onnx_path, TinyOnnx(false));
  const CnnNetwork network(options);
  EXPECT_EQ(network.DescriptorDim(), 3);
  // A PNG whose colour is mostly red: after swap_rb, channel 0 is red.
  cv::Mat image(48, 64, CV_8UC3, cv::Scalar(10, 20, 250));  // BGR
  std::vector<uchar> png;
  ASSERT_TRUE(cv::imencode(".png", image, png));
  const std::string bytes(png.begin(), png.end());
  const Eigen::RowVectorXf descriptor =
      network.DescribeEncoded(bytes, "red.png");
  EXPECT_NEAR(descriptor.norm(), 1.f, 1e-6);
  EXPECT_GT(descriptor(0), 0.99f);  // only red is above the mean 127.5
  options.num_threads = 2;
  options.batch_size = 2;
  const FloatMatrix batch = CnnNetwork(options).DescribeEncodedBatch(
      {{bytes, "a.png"}, {bytes, "b.png"}, {bytes, "c.png"}});
  for (int i = 0; i < 3; ++i) EXPECT_EQ(batch.row(i), descriptor);
}

TEST(CnnEmbedding, OutputThatIsNoDescriptorIsRefused) {
  const TemporaryDirectory dir;
  CnnEmbeddingOptions options;
  options.onnx_path = JoinPaths(dir.Path(), "tokens.onnx");
  WriteFile(options.onnx_path, TinyOnnx(true));
  test::ExpectErrorContaining(
      [&] { CnnNetwork network(options); },
      options.onnx_path +
          " outputs 1x3x4096; expected a feature map 1xCxHxW or a vector 1xC");
}

TEST(CnnEmbeddingOptions, CheckNamesTheField) {
  CnnEmbeddingOptions options;
  EXPECT_NO_THROW(options.Check());
  auto expect_error = [](CnnEmbeddingOptions bad, const std::string& text) {
    try {
      bad.Check();
      ADD_FAILURE() << "no error for " << text;
    } catch (const OptionError& error) {
      EXPECT_NE(std::string(error.what()).find(text), std::string::npos)
          << error.what();
    }
  };
  CnnEmbeddingOptions bad = options;
  bad.max_image_size = 16;
  expect_error(bad, "max_image_size must be >= 32");
  bad = options;
  bad.size_multiple = 0;
  expect_error(bad, "size_multiple must be >= 1");
  bad = options;
  bad.scale = 0;
  expect_error(bad, "scale must be > 0");
  bad = options;
  bad.mean = 300;
  expect_error(bad, "mean must be in [0, 255]");
  bad = options;
  bad.gem_p = 0.5;
  expect_error(bad, "gem_p must be >= 1");
  bad = options;
  bad.pca_dim = -1;
  expect_error(bad, "pca_dim must be >= 0");
  bad = options;
  bad.batch_size = 0;
  expect_error(bad, "batch_size must be >= 1");
  bad = options;
  bad.num_threads = 0;
  expect_error(bad, "num_threads must be -1 (all cores) or >= 1");
}

TEST(CnnEmbedding, InputSizeKeepsAspectOnMultiples) {
  CnnEmbeddingOptions options;  // 512, multiples of 32
  EXPECT_EQ(CnnInputSize(640, 480, options), std::make_pair(512, 384));
  EXPECT_EQ(CnnInputSize(480, 640, options), std::make_pair(384, 512));
  EXPECT_EQ(CnnInputSize(3072, 2048, options), std::make_pair(512, 352));
  EXPECT_EQ(CnnInputSize(100, 100, options), std::make_pair(512, 512));
  // A very thin image still gets one stride.
  EXPECT_EQ(CnnInputSize(4000, 10, options), std::make_pair(512, 32));
  options.max_image_size = 224;
  options.size_multiple = 14;
  EXPECT_EQ(CnnInputSize(640, 480, options), std::make_pair(224, 168));
}

TEST(CnnEmbedding, MissingOrCorruptNetworkIsOneLineError) {
  const TemporaryDirectory dir;
  CnnEmbeddingOptions options;
  test::ExpectErrorContaining([&] { CnnNetwork network(options); },
                              "no ONNX network given");
  options.onnx_path = JoinPaths(dir.Path(), "missing.onnx");
  test::ExpectErrorContaining([&] { CnnNetwork network(options); },
                              "ONNX network not found: " + options.onnx_path);
  options.onnx_path = JoinPaths(dir.Path(), "corrupt.onnx");
  WriteFile(options.onnx_path, "this is not a protobuf at all");
  test::ExpectErrorContaining(
      [&] { CnnNetwork network(options); },
      "cannot read " + options.onnx_path + " as an ONNX network");
  WriteFile(options.onnx_path, "");
  test::ExpectErrorContaining(
      [&] { CnnNetwork network(options); },
      "cannot read " + options.onnx_path + " as an ONNX network");
}

CnnEmbeddingModel FakeModel(bool with_pca) {
  CnnEmbeddingModel model;
  model.network_name = "net.onnx";
  model.network_checksum = 0x1234abcdULL;
  model.descriptor_dim = 4;
  model.options.max_image_size = 320;
  model.options.gem_p = 2;
  model.options.swap_rb = false;
  if (with_pca) {
    model.pca.mean = Eigen::RowVectorXf::Constant(4, 0.1f);
    model.pca.projection = FloatMatrix::Random(2, 4);
    model.pca.eigenvalues = Eigen::VectorXf::Ones(2);
  }
  return model;
}

TEST(CnnEmbeddingModel, SerializeRoundTripAndErrors) {
  for (const bool with_pca : {false, true}) {
    const CnnEmbeddingModel model = FakeModel(with_pca);
    const std::string bytes = model.Serialize();
    const CnnEmbeddingModel read =
        CnnEmbeddingModel::Deserialize(bytes, "blob");
    EXPECT_EQ(read.network_name, "net.onnx");
    EXPECT_EQ(read.network_checksum, model.network_checksum);
    EXPECT_EQ(read.descriptor_dim, 4);
    EXPECT_EQ(read.options.max_image_size, 320);
    EXPECT_EQ(read.options.gem_p, 2);
    EXPECT_FALSE(read.options.swap_rb);
    EXPECT_TRUE(read.options.center);
    EXPECT_EQ(read.OutputDim(), with_pca ? 2 : 4);
    EXPECT_EQ(read.Serialize(), bytes);
    if (with_pca) {
      EXPECT_EQ(read.pca.projection, model.pca.projection);
    }
    std::string corrupt = bytes;
    corrupt[20] ^= 1;
    test::ExpectErrorContaining(
        [&] { CnnEmbeddingModel::Deserialize(corrupt, "blob"); },
        "blob is corrupt (checksum mismatch)");
    test::ExpectErrorContaining(
        [&] { CnnEmbeddingModel::Deserialize("CGCNVLAD....", "blob"); },
        "blob is not a CNN embedding configuration (bad magic)");
  }
}

TEST(CnnEmbeddingModel, ApplyCentresProjectsAndNormalises) {
  CnnEmbeddingModel model = FakeModel(false);
  FloatMatrix raw(3, 4);
  raw << 1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1;
  // The shared last dimension disappears with the mean.
  EmbeddingMatrix centred = model.Apply(raw);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(centred.row(i).norm(), 1.f, 1e-6);
    EXPECT_NEAR(centred(i, 3), 0.f, 1e-6);
  }
  model.options.center = false;
  EXPECT_NEAR(model.Apply(raw)(0, 3), 1.f / std::sqrt(2.f), 1e-6);
  model = FakeModel(true);
  const EmbeddingMatrix projected = model.Apply(raw);
  ASSERT_EQ(projected.cols(), 2);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(projected.row(i).norm(), 1.f, 1e-5);
}

TEST(CnnEmbedding, ConcatenationHalvesEachPart) {
  EmbeddingMatrix a(2, 2), b(2, 3);
  a << 3, 4, 0, 0;
  b << 1, 0, 0, 0, 2, 0;
  const EmbeddingMatrix c = ConcatenateEmbeddings(a, b);
  ASSERT_EQ(c.cols(), 5);
  EXPECT_NEAR(c.row(0).norm(), 1.f, 1e-6);
  EXPECT_NEAR(c.row(0).head(2).norm(), 1.f / std::sqrt(2.f), 1e-6);
  EXPECT_NEAR(c(0, 0), 0.6f / std::sqrt(2.f), 1e-6);
  // A zero part stays zero; the other keeps its half.
  EXPECT_EQ(c.row(1).head(2).norm(), 0.f);
  EXPECT_NEAR(c(1, 3), 1.f / std::sqrt(2.f), 1e-6);
}

// With ../shared: a few real photos of two scenes.
class CnnSharedTest : public testing::Test {
 protected:
  void SetUp() override {
    if (SharedNetworkPath().empty()) return;
    const std::string datasets = test::SharedDatasetsDir();
    for (const std::string scene : {"dino-sparse-ring", "cake"}) {
      const std::string dir = JoinPaths(datasets, scene + "/images");
      std::vector<std::string> names;
      for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        names.push_back(entry.path().filename().string());
      }
      std::sort(names.begin(), names.end());
      for (int i = 0; i < 4; ++i) {
        const std::string name = scene + "-" + names[i];
        std::filesystem::copy_file(JoinPaths(dir, names[i]),
                                   JoinPaths(dir_.Path(), name));
        names_.push_back(name);
        scene_.push_back(scene == "cake" ? 1 : 0);
      }
    }
    options_.onnx_path = SharedNetworkPath();
    options_.progress_every = 0;
  }

  std::vector<std::pair<std::string, std::string>> Items() const {
    std::vector<std::pair<std::string, std::string>> items;
    for (const auto& name : names_) {
      items.emplace_back(ReadTextFile(JoinPaths(dir_.Path(), name)), name);
    }
    return items;
  }

  TemporaryDirectory dir_;
  std::vector<std::string> names_;
  std::vector<int> scene_;
  CnnEmbeddingOptions options_;
};

TEST_F(CnnSharedTest, EmbedsUnitVectorsThatSeparateScenes) {
  SKIP_WITHOUT_NETWORK();
  options_.num_threads = 1;
  const CnnNetwork network(options_);
  EXPECT_EQ(network.DescriptorDim(), 1280);
  EXPECT_EQ(network.NetworkChecksum(), FileChecksum(options_.onnx_path));
  const FloatMatrix raw = network.DescribeEncodedBatch(Items());
  ASSERT_EQ(raw.rows(), 8);
  ASSERT_EQ(raw.cols(), 1280);
  const EmbeddingMatrix embeddings = MakeCnnEmbeddingModel(network).Apply(raw);
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(raw.row(i).norm(), 1.f, 1e-5);
    EXPECT_NEAR(embeddings.row(i).norm(), 1.f, 1e-5);
  }
  // Every image's least similar same-scene image beats its most similar
  // image of the other scene.
  const Eigen::MatrixXf similarity = embeddings * embeddings.transpose();
  for (int i = 0; i < 8; ++i) {
    float min_same = 2, max_other = -2;
    for (int j = 0; j < 8; ++j) {
      if (i == j) continue;
      if (scene_[i] == scene_[j]) {
        min_same = std::min(min_same, similarity(i, j));
      } else {
        max_other = std::max(max_other, similarity(i, j));
      }
    }
    EXPECT_GT(min_same, max_other) << names_[i];
  }
}

TEST_F(CnnSharedTest, IdenticalForAnyThreadCountAndBatchSize) {
  SKIP_WITHOUT_NETWORK();
  options_.num_threads = 1;
  const FloatMatrix one = CnnNetwork(options_).DescribeEncodedBatch(Items());
  options_.num_threads = 2;
  const FloatMatrix two = CnnNetwork(options_).DescribeEncodedBatch(Items());
  EXPECT_EQ(one, two);
  options_.batch_size = 3;
  const FloatMatrix batched =
      CnnNetwork(options_).DescribeEncodedBatch(Items());
  EXPECT_EQ(one, batched);
}

TEST_F(CnnSharedTest, UnreadableImagesAreNamed) {
  SKIP_WITHOUT_NETWORK();
  const CnnNetwork network(options_);
  test::ExpectErrorContaining(
      [&] { network.DescribeEncoded("not an image", "broken.jpg"); },
      "cannot decode image broken.jpg");
  const std::string db = JoinPaths(dir_.Path(), "db.db");
  test::CreateDescriptorDatabase(
      db,
      {{names_[0], test::RandomDescriptors(10, 2, 1)},
       {"missing.jpg", test::RandomDescriptors(10, 2, 2)}});
  std::vector<image_t> ids;
  test::ExpectErrorContaining(
      [&] {
        ComputeDatabaseCnnDescriptors(
            Database(db), network, dir_.Path(), "", &ids);
      },
      "cannot read image missing.jpg");
  test::ExpectErrorContaining(
      [&] {
        ComputeDatabaseCnnDescriptors(Database(db), network, "", "", &ids);
      },
      "--GcnMatching.image_path");
}

TEST_F(CnnSharedTest, CacheReturnsIdenticalBytesAndMissesChangedFiles) {
  SKIP_WITHOUT_NETWORK();
  const std::string db = JoinPaths(dir_.Path(), "db.db");
  std::vector<std::pair<std::string, FeatureDescriptors>> images;
  for (size_t i = 0; i < names_.size(); ++i) {
    images.emplace_back(names_[i], test::RandomDescriptors(10, 2, i));
  }
  test::CreateDescriptorDatabase(db, images);
  options_.num_threads = 2;
  const CnnNetwork network(options_);
  const std::string cache = DefaultCnnCachePath(db);
  std::vector<image_t> ids1, ids2;
  EmbeddingCacheStats stats;
  const FloatMatrix first = ComputeDatabaseCnnDescriptors(
      Database(db), network, dir_.Path(), cache, &ids1, &stats);
  EXPECT_EQ(stats.num_computed, 8u);
  EXPECT_EQ(stats.num_cached, 0u);
  ASSERT_TRUE(ExistsFile(cache));
  const FloatMatrix second = ComputeDatabaseCnnDescriptors(
      Database(db), network, dir_.Path(), cache, &ids2, &stats);
  EXPECT_EQ(stats.num_cached, 8u);
  EXPECT_EQ(stats.num_computed, 0u);
  EXPECT_EQ(first, second);
  EXPECT_EQ(ids1, ids2);
  EXPECT_EQ(first, network.DescribeEncodedBatch(Items()));
  // Entries are keyed on file content: another image's bytes under the
  // first name reuse that image's descriptor.
  const std::string first_path = JoinPaths(dir_.Path(), names_[0]);
  const std::string original = ReadTextFile(first_path);
  std::filesystem::copy_file(JoinPaths(dir_.Path(), names_[5]),
                             first_path,
                             std::filesystem::copy_options::overwrite_existing);
  const FloatMatrix third = ComputeDatabaseCnnDescriptors(
      Database(db), network, dir_.Path(), cache, &ids2, &stats);
  EXPECT_EQ(stats.num_cached, 8u);
  EXPECT_EQ(third.row(0), first.row(5));
  // Changed bytes (trailing junk the decoder ignores) miss for that image
  // only.
  WriteFile(first_path, original + "junk");
  const FloatMatrix fourth = ComputeDatabaseCnnDescriptors(
      Database(db), network, dir_.Path(), cache, &ids2, &stats);
  EXPECT_EQ(stats.num_computed, 1u);
  EXPECT_EQ(stats.num_cached, 7u);
  EXPECT_EQ(fourth, first);
  // Another configuration misses everything.
  options_.max_image_size = 256;
  const CnnNetwork smaller(options_);
  ComputeDatabaseCnnDescriptors(
      Database(db), smaller, dir_.Path(), cache, &ids2, &stats);
  EXPECT_EQ(stats.num_computed, 8u);
}

TEST_F(CnnSharedTest, FailedRunKeepsWhatItComputed) {
  SKIP_WITHOUT_NETWORK();
  // 20 images (the 8 files, repeated under new names), the 17th missing:
  // the run fails naming it, and the next one reuses everything before it.
  const std::string db = JoinPaths(dir_.Path(), "db.db");
  std::vector<std::pair<std::string, FeatureDescriptors>> images;
  for (int i = 0; i < 20; ++i) {
    const std::string name = "copy" + std::to_string(100 + i) + ".img";
    if (i != 16) {
      std::filesystem::copy_file(JoinPaths(dir_.Path(), names_[i % 8]),
                                 JoinPaths(dir_.Path(), name));
    }
    images.emplace_back(name, test::RandomDescriptors(10, 2, i));
  }
  test::CreateDescriptorDatabase(db, images);
  options_.num_threads = 1;  // chunks of 8 images
  const CnnNetwork network(options_);
  const std::string cache = DefaultCnnCachePath(db);
  std::vector<image_t> ids;
  test::ExpectErrorContaining(
      [&] {
        ComputeDatabaseCnnDescriptors(
            Database(db), network, dir_.Path(), cache, &ids);
      },
      "cannot read image copy116.img");
  ASSERT_TRUE(ExistsFile(cache));
  std::filesystem::copy_file(JoinPaths(dir_.Path(), names_[0]),
                             JoinPaths(dir_.Path(), "copy116.img"));
  EmbeddingCacheStats stats;
  const FloatMatrix resumed = ComputeDatabaseCnnDescriptors(
      Database(db), network, dir_.Path(), cache, &ids, &stats);
  // The first two chunks (16 images; 8 distinct files) were kept; the
  // rest are copies of those files too, so they hit as well.
  EXPECT_EQ(stats.num_cached, 20u);
  EXPECT_EQ(stats.num_computed, 0u);
  EXPECT_EQ(resumed.row(16), resumed.row(0));
}

TEST_F(CnnSharedTest, ModelRefusesAnotherNetwork) {
  SKIP_WITHOUT_NETWORK();
  const CnnNetwork network(options_);
  std::vector<FloatMatrix> collections = {
      network.DescribeEncodedBatch(Items())};
  CnnEmbeddingOptions pca_options = options_;
  pca_options.pca_dim = 4;
  const CnnNetwork pca_network(pca_options);
  const CnnEmbeddingModel model =
      TrainCnnEmbeddingModel(pca_network, collections);
  EXPECT_EQ(model.OutputDim(), 4);
  EXPECT_EQ(model.network_name, "mobilenet_v2_imagenet_features.onnx");
  EXPECT_NO_THROW(model.CheckNetwork(network, "--GcnMatching.onnx_path"));
  const EmbeddingMatrix embedded = model.Apply(collections[0]);
  EXPECT_EQ(embedded.cols(), 4);
  EXPECT_NEAR(embedded.row(0).norm(), 1.f, 1e-5);

  // The same network with one byte changed is another network.
  std::string bytes = ReadTextFile(options_.onnx_path);
  const std::string other = JoinPaths(dir_.Path(), "other.onnx");
  bytes += std::string("\x32\x01x", 3);  // ModelProto.doc_string = "x"

  WriteFile(other, bytes);
  CnnEmbeddingOptions other_options = options_;
  other_options.onnx_path = other;
  CnnNetwork other_network(other_options);
  test::ExpectErrorContaining(
      [&] { model.CheckNetwork(other_network, "--GcnMatching.onnx_path"); },
      "the model was trained on mobilenet_v2_imagenet_features.onnx "
      "(checksum " +
          FormatChecksum(network.NetworkChecksum()) +
          ") but --GcnMatching.onnx_path is " + other + " (checksum " +
          FormatChecksum(other_network.NetworkChecksum()) + ")");
}

}  // namespace
}  // namespace colmap_gcn
