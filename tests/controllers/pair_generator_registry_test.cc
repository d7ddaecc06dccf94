#include "controllers/pair_generators.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "../retrieval/retrieval_test_utils.h"
#include "controllers/gcn_matching.h"
#include "controllers/vocab_tree_pairing.h"
#include "pairing/gcn_model_pairing.h"
#include "pairing/imported_pairing.h"
#include "pairing/knn_pairing.h"
#include "pairing/pair_generator_registry.h"
#include "pairing/pairing.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/option_check.h"
#include "util/option_manager.h"

namespace colmap_gcn {
namespace {

// A database of 6 images with SIFT-like descriptors.
class PairGeneratorRegistryTest : public testing::Test {
 protected:
  void SetUp() override {
    database_path_ = JoinPaths(dir_.Path(), "database.db");
    test::CreateRandomDescriptorDatabase(database_path_, 6, 200, 8, 20);
  }

  TemporaryDirectory dir_{"colmap_gcn_registry"};
  std::string database_path_;
};

TEST(PairGeneratorRegistry, NamesTheBuiltInGeneratorsAndTheDefault) {
  const std::vector<std::string> names = PairGenerators().Names();
  ASSERT_GE(names.size(), 5u);
  EXPECT_EQ(names.front(), "gcn");
  EXPECT_TRUE(PairGenerators().Has(kDefaultPairing));
  EXPECT_TRUE(PairGenerators().UsesVerification(kDefaultPairing));
  for (const char* name : {"exhaustive", "imported", "knn", "vocab_tree"}) {
    EXPECT_TRUE(PairGenerators().Has(name)) << name;
  }
  EXPECT_EQ(GcnMatchingOptions().pairing, "adaptive");
}

TEST(PairGeneratorRegistry, UnknownNameIsOneLineListingTheKnownNames) {
  const PairGeneratorOptions options = PairGenerators().DefaultOptions();
  try {
    PairGenerators().Check("bogus", options);
    FAIL() << "no error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find("\"bogus\""), std::string::npos) << message;
    for (const std::string& name : PairGenerators().Names()) {
      EXPECT_NE(message.find(name), std::string::npos) << message;
    }
  }
  // Through the options a command checks: the flag's own error.
  GcnMatchingOptions matching;
  matching.pairing = "bogus";
  test::ExpectErrorContaining([&] { matching.Check(); },
                              "pairing must be one of gcn|exhaustive|");
}

TEST(PairGeneratorRegistry, DefaultOptionsAreValidExceptImportedsFile) {
  const PairGeneratorOptions options = PairGenerators().DefaultOptions();
  for (const std::string& name : PairGenerators().Names()) {
    if (name == "imported") {
      test::ExpectErrorContaining(
          [&] { PairGenerators().Check(name, options); },
          "match_list_path must name a pairs file");
    } else {
      EXPECT_NO_THROW(PairGenerators().Check(name, options)) << name;
    }
  }
}

TEST(PairGeneratorRegistry, TypedOptionsAndDepth) {
  PairGeneratorOptions options = PairGenerators().DefaultOptions();
  options.Get<KnnPairingOptions>("knn").k = 7;
  EXPECT_EQ(*PairGenerators().Depth("knn", &options), 7);
  EXPECT_EQ(PairGenerators().Depth("knn", &options),
            &options.Get<KnnPairingOptions>("knn").k);
  EXPECT_EQ(PairGenerators().Depth("vocab_tree", &options),
            &options.Get<VocabTreePairingOptions>("vocab_tree").k);
  EXPECT_EQ(PairGenerators().Depth("gcn", &options), nullptr);
  EXPECT_FALSE(PairGenerators().IsBenchmarkMethod("imported"));
  // Asking for the wrong type is an error, not a bad cast.
  EXPECT_THROW(options.Get<KnnPairingOptions>("gcn"), Error);
}

// Every registered flag on one command line, shared flags set everywhere.
TEST(PairGeneratorRegistry, FlagsBindEveryGeneratorsOptions) {
  GcnMatchingOptions options;
  OptionManager manager("test", "");
  manager.AddDefaultOption("GcnMatching.pairing", &options.pairing);
  PairGenerators().AddOptions(&manager, &options.generators);
  std::vector<std::string> args = {"test",
                                   "--GcnMatching.pairing",
                                   "knn",
                                   "--GcnMatching.k",
                                   "9",
                                   "--GcnMatching.num_threads",
                                   "2",
                                   "--GcnMatching.k1",
                                   "40"};
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  ASSERT_TRUE(manager.Parse(static_cast<int>(argv.size()), argv.data()));
  const PairGeneratorOptions& generators = options.generators;
  EXPECT_EQ(options.pairing, "knn");
  EXPECT_EQ(generators.Get<KnnPairingOptions>("knn").k, 9);
  EXPECT_EQ(generators.Get<VocabTreePairingOptions>("vocab_tree").k, 9);
  EXPECT_EQ(generators.Get<KnnPairingOptions>("knn").num_threads, 2);
  EXPECT_EQ(generators.Get<GcnModelPairingOptions>("gcn").num_threads, 2);
  EXPECT_EQ(generators.Get<GcnModelPairingOptions>("gcn").k1, 40);
  EXPECT_TRUE(manager.IsGiven("GcnMatching.k"));
  EXPECT_FALSE(manager.IsGiven("GcnMatching.k2"));
  // A field's error names the flag bound to it.
  options.generators.Get<KnnPairingOptions>("knn").k = 0;
  test::ExpectErrorContaining([&] { manager.Check([&] { options.Check(); }); },
                              "--GcnMatching.k must be >= 1 (got 0)");
}

// The embedding flags reach the GCN's options (checked against the model)
// and knn's (resolved into its descriptor options).
TEST(PairGeneratorRegistry, EmbeddingFlagsBindGcnAndKnn) {
  GcnMatchingOptions options;
  OptionManager manager("test", "");
  manager.AddDefaultOption("GcnMatching.pairing", &options.pairing);
  PairGenerators().AddOptions(&manager, &options.generators);
  std::vector<std::string> args = {"test",
                                   "--GcnMatching.embedding",
                                   "vlad+onnx",
                                   "--GcnMatching.onnx_path",
                                   "net.onnx",
                                   "--GcnMatching.image_path",
                                   "images",
                                   "--GcnMatching.onnx_max_image_size",
                                   "640",
                                   "--GcnMatching.onnx_batch_size",
                                   "4"};
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  ASSERT_TRUE(manager.Parse(static_cast<int>(argv.size()), argv.data()));
  const auto& gcn = options.generators.Get<GcnModelPairingOptions>("gcn");
  EXPECT_EQ(gcn.embedding.type, EmbeddingType::kVladOnnx);
  EXPECT_EQ(gcn.embedding.onnx_path, "net.onnx");
  EXPECT_EQ(gcn.embedding.image_path, "images");
  EXPECT_EQ(gcn.embedding.onnx.max_image_size, 640);
  EXPECT_EQ(gcn.embedding.onnx.gem_p, -1);  // unset: the model's
  EXPECT_EQ(gcn.embedding.onnx_batch_size, 4);
  const auto& knn = options.generators.Get<KnnPairingOptions>("knn");
  const GlobalDescriptorOptions descriptors = knn.Descriptors();
  EXPECT_EQ(descriptors.embedding, EmbeddingType::kVladOnnx);
  EXPECT_EQ(descriptors.cnn.onnx_path, "net.onnx");
  EXPECT_EQ(descriptors.image_path, "images");
  EXPECT_EQ(descriptors.cnn.max_image_size, 640);
  EXPECT_EQ(descriptors.cnn.gem_p, CnnEmbeddingOptions().gem_p);
  EXPECT_EQ(descriptors.cnn.batch_size, 4);
  EXPECT_NO_THROW(options.Check());
  options.pairing = "knn";
  EXPECT_NO_THROW(options.Check());
}

TEST(PairGeneratorRegistry, KnnEmbeddingChoices) {
  KnnPairingOptions knn;
  // default keeps vlad
  EXPECT_EQ(knn.Descriptors().embedding, EmbeddingType::kVlad);
  knn.embedding.type = EmbeddingType::kImported;
  test::ExpectErrorContaining([&] { knn.Check(); },
                              "descriptor_path must name the descriptor file");
  knn.embedding.descriptor_path = "x.h5";
  EXPECT_NO_THROW(knn.Check());
  // the import takes over
  EXPECT_EQ(knn.Descriptors().embedding, EmbeddingType::kVlad);
  EXPECT_EQ(knn.Descriptors().descriptor_path, "x.h5");
  knn.embedding.type = EmbeddingType::kOnnx;
  test::ExpectErrorContaining([&] { knn.Check(); },
                              "onnx_path must name the ONNX network");
  knn.embedding.onnx_path = "net.onnx";
  knn.embedding.image_path = "images";
  EXPECT_NO_THROW(knn.Check());
  test::ExpectErrorContaining([&] { knn.Descriptors(); },
                              "cannot be combined with "
                              "--GcnMatching.embedding onnx");
  // An unknown name fails where the flag is parsed, once.
  test::ExpectErrorContaining(
      [&] {
        ParseEnum(EmbeddingTypeNames(), "sift", "--GcnMatching.embedding");
      },
      "must be one of default|vlad|onnx|vlad+onnx|imported (got \"sift\")");
}

// Each generator that needs no COLMAP creates from its defaults (imported
// from a pairs file) and yields valid pairs of the database's images.
TEST_F(PairGeneratorRegistryTest, EachGeneratorCreatesFromDefaultOptions) {
  const Database database(database_path_);
  PairGeneratorContext context(database);
  PairGeneratorOptions options = PairGenerators().DefaultOptions();
  const std::string pairs_path = JoinPaths(dir_.Path(), "pairs.txt");
  WriteFileAtomically(pairs_path,
                      "image0.jpg image1.jpg\nimage2.jpg image5.jpg\n");
  options.Get<ImagePairsMatchingOptions>("imported").match_list_path =
      pairs_path;
  for (const std::string& name : PairGenerators().Names()) {
    // Runs COLMAP: PairGeneratorRegistryTest.VocabTreeCreatesWithColmap.
    if (name == "vocab_tree") continue;
    if (name == "gcn" && DefaultGcnModelPath().empty()) {
      ADD_FAILURE() << "no default model in the source tree";
      continue;
    }
    const std::vector<ImagePair> pairs =
        PairGenerators().Create(name, options, context)->AllPairs();
    EXPECT_FALSE(pairs.empty()) << name;
    for (const auto& [a, b] : pairs) {
      EXPECT_NE(a, b) << name;
      EXPECT_GE(std::min(a, b), 1u) << name;
      EXPECT_LE(std::max(a, b), 6u) << name;
    }
    if (name == "exhaustive") {
      EXPECT_EQ(pairs.size(), 15u);
    }
    if (name == "imported") {
      EXPECT_EQ(pairs.size(), 2u);
    }
  }
}

TEST_F(PairGeneratorRegistryTest, VocabTreeCreatesWithColmap) {
  if (test::RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
  const Database database(database_path_);
  PairGeneratorContext context(database);
  context.colmap_log_path = JoinPaths(dir_.Path(), "colmap.log");
  PairGeneratorOptions options = PairGenerators().DefaultOptions();
  options.Get<VocabTreePairingOptions>("vocab_tree").k = 2;
  const std::vector<ImagePair> pairs =
      PairGenerators().Create("vocab_tree", options, context)->AllPairs();
  EXPECT_GE(pairs.size(), 6u);
  EXPECT_LE(pairs.size(), 12u);
}

TEST(PairGeneratorRegistry, PrepareRunsOnlyTheGeneratorsOwnStep) {
  struct Options {
    std::string path;
    void Check() const {}
  };
  PairGeneratorRegistry registry;
  PairGeneratorSpec<Options> with;
  with.name = "with";
  with.create = [](const Options&, const PairGeneratorContext&) {
    return std::unique_ptr<PairGenerator>();
  };
  with.prepare = [](Options* options, const PairGeneratorContext&) {
    options->path = "prepared";
  };
  PairGeneratorSpec<Options> without = with;
  without.name = "without";
  without.prepare = nullptr;
  registry.Register(with);
  registry.Register(without);
  TemporaryDirectory dir;
  const std::string database_path = JoinPaths(dir.Path(), "database.db");
  test::CreateDescriptorDatabase(database_path, {});
  const Database database(database_path);
  const PairGeneratorContext context(database);
  PairGeneratorOptions options = registry.DefaultOptions();
  EXPECT_TRUE(registry.Prepare("with", &options, context));
  EXPECT_EQ(options.Get<Options>("with").path, "prepared");
  EXPECT_FALSE(registry.Prepare("without", &options, context));
  EXPECT_EQ(options.Get<Options>("without").path, "");
}

}  // namespace
}  // namespace colmap_gcn
