#include "retrieval/model_embedding.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "retrieval_test_utils.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

const char kNetworkFile[] = "mobilenet_v2_imagenet_features.onnx";

std::string SharedNetworkPath() {
  const std::string datasets = test::SharedDatasetsDir();
  if (datasets.empty()) return "";
  const std::string path =
      JoinPaths(datasets, std::string("../models/") + kNetworkFile);
  return ExistsFile(path) ? path : "";
}

VladEmbedding SmallVlad() {
  PcaWhitening pca;
  pca.mean = Eigen::RowVectorXf::Zero(2 * 128);
  pca.projection = FloatMatrix::Random(3, 2 * 128);
  pca.eigenvalues = Eigen::VectorXf::Ones(3);
  return VladEmbedding(FloatMatrix::Random(2, 128).cwiseAbs(), pca);
}

CnnEmbeddingModel FakeCnn(uint64_t checksum) {
  CnnEmbeddingModel model;
  model.network_name = kNetworkFile;
  model.network_checksum = checksum;
  model.descriptor_dim = 1280;
  return model;
}

TEST(ModelEmbedding, ConfigTypesAndDimensions) {
  const VladEmbedding vlad = SmallVlad();
  const CnnEmbeddingModel cnn = FakeCnn(1);
  const GcnEmbeddingConfig v = MakeEmbeddingConfig(&vlad, nullptr);
  EXPECT_EQ(v.type, "vlad");
  EXPECT_EQ(v.dim, 3);
  const GcnEmbeddingConfig c = MakeEmbeddingConfig(nullptr, &cnn);
  EXPECT_EQ(c.type, "onnx");
  EXPECT_EQ(c.dim, 1280);
  const GcnEmbeddingConfig both = MakeEmbeddingConfig(&vlad, &cnn);
  EXPECT_EQ(both.type, "vlad+onnx");
  EXPECT_EQ(both.dim, 1283);
  // A VLAD model needs nothing else.
  EXPECT_EQ(ModelEmbedder(v, ModelEmbeddingOptions()).Type(),
            EmbeddingType::kVlad);
}

TEST(ModelEmbedding, EveryListedEmbeddingIsRegistered) {
  for (const auto& [name, type] : EmbeddingTypeNames()) {
    if (type == EmbeddingType::kDefault) {
      EXPECT_THROW(GetEmbeddingSpec(type), Error);
      continue;
    }
    const EmbeddingSpec& spec = GetEmbeddingSpec(type);
    EXPECT_TRUE(spec.load) << name;
    EXPECT_TRUE(spec.build) << name;
    // A model's config names the embedding, optionally with a detail.
    GcnEmbeddingConfig config;
    config.type = name;
    EXPECT_EQ(EmbeddingConfigType(config), type);
    config.type = name + ":detail";
    EXPECT_EQ(EmbeddingConfigType(config), type);
  }
}

TEST(ModelEmbedding, ErrorsNameWhatIsMissingOrDifferent) {
  const VladEmbedding vlad = SmallVlad();
  const CnnEmbeddingModel cnn = FakeCnn(1);
  ModelEmbeddingOptions options;
  test::ExpectErrorContaining(
      [&] { ModelEmbedder(MakeEmbeddingConfig(nullptr, &cnn), options); },
      "the GCN model embeds images with the ONNX network "
      "mobilenet_v2_imagenet_features.onnx (checksum 0000000000000001); "
      "pass it with --GcnMatching.onnx_path");
  // The concatenated blob splits: its CNN part asks for the network too.
  test::ExpectErrorContaining(
      [&] { ModelEmbedder(MakeEmbeddingConfig(&vlad, &cnn), options); },
      "pass it with --GcnMatching.onnx_path");
  options.embedding.type = EmbeddingType::kVlad;
  test::ExpectErrorContaining(
      [&] { ModelEmbedder(MakeEmbeddingConfig(nullptr, &cnn), options); },
      "the GCN model embeds with onnx but --GcnMatching.embedding is vlad");
  options.embedding.type = EmbeddingType::kDefault;
  options.embedding.onnx_path = "/nonexistent/net.onnx";
  options.embedding.onnx.max_image_size = 640;
  test::ExpectErrorContaining(
      [&] { ModelEmbedder(MakeEmbeddingConfig(nullptr, &cnn), options); },
      "the GCN model was trained with --GcnMatching.onnx_max_image_size 512 "
      "but it is 640");
  options.embedding.onnx.max_image_size =
      512;  // set to the model's value: accepted
  test::ExpectErrorContaining(
      [&] { ModelEmbedder(MakeEmbeddingConfig(nullptr, &cnn), options); },
      "ONNX network not found: /nonexistent/net.onnx");

  GcnEmbeddingConfig config = MakeEmbeddingConfig(&vlad, &cnn);
  config.blob.resize(config.blob.size() / 2);
  test::ExpectErrorContaining(
      [&] { ModelEmbedder(config, ModelEmbeddingOptions()); },
      "the GCN model's vlad+onnx embedding is malformed");
  config.type = "sift-bag";
  test::ExpectErrorContaining(
      [&] { ModelEmbedder(config, ModelEmbeddingOptions()); },
      "unknown embedding type \"sift-bag\"");
  config.type = "imported:netvlad";
  test::ExpectErrorContaining(
      [&] { ModelEmbedder(config, ModelEmbeddingOptions()); },
      "pass them with --GcnMatching.descriptor_path");
  options = ModelEmbeddingOptions();
  options.embedding.descriptor_path = "x.h5";
  test::ExpectErrorContaining(
      [&] { ModelEmbedder(MakeEmbeddingConfig(&vlad, nullptr), options); },
      "need a model trained on them");
}

TEST(ModelEmbeddingShared, ConcatenatedRowsAndNetworkChecksum) {
  if (SharedNetworkPath().empty()) {
    GTEST_SKIP() << "../shared/models/" << kNetworkFile << " not found";
  }
  const TemporaryDirectory dir;
  const std::string images =
      JoinPaths(test::SharedDatasetsDir(), "dino-sparse-ring/images");
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(images)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  std::vector<std::pair<std::string, FeatureDescriptors>> db_images;
  for (int i = 0; i < 3; ++i) {
    db_images.emplace_back(names[i], test::RandomDescriptors(50, 3, i));
  }
  const std::string db = JoinPaths(dir.Path(), "db.db");
  test::CreateDescriptorDatabase(db, db_images);

  CnnEmbeddingOptions cnn_options;
  cnn_options.onnx_path = SharedNetworkPath();
  cnn_options.progress_every = 0;
  const CnnEmbeddingModel cnn = MakeCnnEmbeddingModel(CnnNetwork(cnn_options));
  const VladEmbedding vlad = SmallVlad();
  ModelEmbeddingOptions options;
  options.embedding.onnx_path = SharedNetworkPath();
  options.progress_every = 0;
  options.use_vlad_cache = false;
  const ModelEmbedder embedder(MakeEmbeddingConfig(&vlad, &cnn), options);
  std::vector<image_t> ids;
  const EmbeddingMatrix rows =
      embedder.Finalize(embedder.EmbedDatabase(Database(db), images, "", &ids));
  ASSERT_EQ(rows.rows(), 3);
  ASSERT_EQ(rows.cols(), 3 + 1280);
  EXPECT_EQ(ids, (std::vector<image_t>{1, 2, 3}));
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(rows.row(i).norm(), 1.f, 1e-5);
    EXPECT_NEAR(rows.row(i).head(3).norm(), 1.f / std::sqrt(2.f), 1e-5);
  }

  // A model made with another network file refuses this one.
  const CnnEmbeddingModel other = FakeCnn(cnn.network_checksum ^ 1);
  test::ExpectErrorContaining(
      [&] { ModelEmbedder(MakeEmbeddingConfig(nullptr, &other), options); },
      "the model was trained on mobilenet_v2_imagenet_features.onnx "
      "(checksum " +
          FormatChecksum(other.network_checksum) +
          ") but --GcnMatching.onnx_path is " + SharedNetworkPath());
}

}  // namespace
}  // namespace colmap_gcn
