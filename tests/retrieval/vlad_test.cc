#include "retrieval/vlad.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "retrieval_test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

// A hand-made model: 3 words, whitening 4 x 384 with random entries.
VladEmbedding HandMadeModel() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uniform(-1, 1);
  FloatMatrix codebook(3, 128);
  for (int w = 0; w < 3; ++w) {
    for (int c = 0; c < 128; ++c) {
      // Word w puts its mass on dimensions [40 w, 40 w + 40).
      codebook(w, c) = (c >= 40 * w && c < 40 * w + 40) ? 0.15f : 0.01f;
    }
  }
  PcaWhitening pca;
  pca.mean.resize(3 * 128);
  for (int i = 0; i < pca.mean.size(); ++i) pca.mean(i) = 0.01f * uniform(rng);
  pca.projection.resize(4, 3 * 128);
  for (int i = 0; i < pca.projection.size(); ++i) {
    pca.projection.data()[i] = uniform(rng);
  }
  pca.eigenvalues = Eigen::VectorXf::Ones(4);
  return VladEmbedding(codebook, pca);
}

FeatureDescriptors HandMadeDescriptors() {
  FeatureDescriptors d = FeatureDescriptors::Zero(5, 128);
  for (int c = 0; c < 128; ++c) {
    d(0, c) = c < 40 ? 50 : 1;               // word 0
    d(1, c) = c < 40 ? 20 + c % 7 : 2;       // word 0
    d(2, c) = (c >= 40 && c < 80) ? 90 : 0;  // word 1
    d(3, c) = c >= 80 && c < 120 ? 33 : 3;   // word 2
    d(4, c) = static_cast<uint8_t>(c % 11);  // spread out
  }
  return d;
}

// The pipeline written out with plain loops in double.
std::vector<double> DirectEmbedding(const VladEmbedding& model,
                                    const FeatureDescriptors& descriptors) {
  const FloatMatrix& codebook = model.Codebook();
  const int num_words = 3;
  std::vector<double> vlad(num_words * 128, 0.0);
  for (int r = 0; r < descriptors.rows(); ++r) {
    double l1 = 0;
    for (int c = 0; c < 128; ++c) l1 += descriptors(r, c);
    std::vector<double> root(128);
    for (int c = 0; c < 128; ++c) root[c] = std::sqrt(descriptors(r, c) / l1);
    int best = -1;
    double best_distance = 1e300;
    for (int w = 0; w < num_words; ++w) {
      double distance = 0;
      for (int c = 0; c < 128; ++c) {
        distance += (root[c] - codebook(w, c)) * (root[c] - codebook(w, c));
      }
      if (distance < best_distance) {
        best_distance = distance;
        best = w;
      }
    }
    for (int c = 0; c < 128; ++c) {
      vlad[best * 128 + c] += root[c] - codebook(best, c);
    }
  }
  for (int w = 0; w < num_words; ++w) {  // intra-normalisation
    double norm = 0;
    for (int c = 0; c < 128; ++c) norm += vlad[w * 128 + c] * vlad[w * 128 + c];
    norm = std::sqrt(norm);
    if (norm > 0) {
      for (int c = 0; c < 128; ++c) vlad[w * 128 + c] /= norm;
    }
  }
  double norm = 0;
  for (double& v : vlad) {  // signed square root
    v = (v > 0 ? 1 : v < 0 ? -1 : 0) * std::sqrt(std::abs(v));
    norm += v * v;
  }
  for (double& v : vlad) v /= std::sqrt(norm);
  std::vector<double> out(4, 0.0);
  double out_norm = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 3 * 128; ++j) {
      out[i] += model.Pca().projection(i, j) * (vlad[j] - model.Pca().mean(j));
    }
    out_norm += out[i] * out[i];
  }
  for (double& v : out) v /= std::sqrt(out_norm);
  return out;
}

TEST(RootSift, NormalisesRowsAndKeepsZeroRows) {
  FeatureDescriptors d = FeatureDescriptors::Zero(2, 128);
  d(0, 0) = 9;
  d(0, 1) = 16;
  const FloatMatrix root = RootSift(d);
  EXPECT_NEAR(root(0, 0), std::sqrt(9.0 / 25), 1e-6);
  EXPECT_NEAR(root(0, 1), std::sqrt(16.0 / 25), 1e-6);
  EXPECT_NEAR(root.row(0).norm(), 1.0, 1e-6);
  EXPECT_EQ(root.row(1).norm(), 0.f);
}

TEST(VladEmbedding, EqualsDirectComputation) {
  const VladEmbedding model = HandMadeModel();
  const FeatureDescriptors descriptors = HandMadeDescriptors();
  const Eigen::RowVectorXf embedding = model.Embed(descriptors);
  const std::vector<double> expected = DirectEmbedding(model, descriptors);
  ASSERT_EQ(embedding.size(), 4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(embedding(i), expected[i], 1e-5);
  EXPECT_NEAR(embedding.norm(), 1.0, 1e-5);
  // Word 1 and word 2 residual blocks each hold one unit-normalised
  // residual; after the signed square root every non-empty block has the
  // same share of the global norm.
  const Eigen::RowVectorXf vlad = model.ComputeVlad(descriptors);
  EXPECT_NEAR(vlad.norm(), 1.0, 1e-5);
}

TEST(VladEmbedding, NoDescriptorsGivesZeroVector) {
  const VladEmbedding model = HandMadeModel();
  EXPECT_EQ(model.Embed(FeatureDescriptors(0, 128)).norm(), 0.f);
  EXPECT_THROW(model.Embed(FeatureDescriptors::Zero(2, 64)), Error);
}

TEST(VladEmbedding, FileRoundTripAndCorruptFiles) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "vlad.bin");
  const VladEmbedding model = HandMadeModel();
  model.Write(path);
  const VladEmbedding read = VladEmbedding::Read(path);
  EXPECT_EQ(read.Checksum(), model.Checksum());
  EXPECT_EQ(read.Embed(HandMadeDescriptors()),
            model.Embed(HandMadeDescriptors()));

  const std::string contents = ReadTextFile(path);
  auto expect_error = [&](const std::string& bytes, const std::string& what) {
    const std::string bad = JoinPaths(dir.Path(), "bad.bin");
    WriteFileAtomically(bad, bytes);
    try {
      VladEmbedding::Read(bad);
      ADD_FAILURE() << "no error for " << what;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(what), std::string::npos)
          << error.what();
      EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos);
    }
  };
  expect_error(contents.substr(0, contents.size() - 100), "truncated");
  expect_error(contents.substr(0, 10), "truncated");
  expect_error("PK\x03\x04 a zip file, not ours", "bad magic");
  expect_error(contents + "x", "too long");
  std::string flipped = contents;
  flipped[200] ^= 0x10;
  expect_error(flipped, "checksum");
  std::string version = contents;
  version[8] = 7;
  expect_error(version, "version 7");
  EXPECT_THROW(VladEmbedding::Read(JoinPaths(dir.Path(), "none.bin")), Error);
}

TEST(VladEmbedding, TrainingIsDeterministicAndThreadIndependent) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "train.db");
  std::vector<std::pair<std::string, FeatureDescriptors>> images;
  for (int i = 0; i < 8; ++i) {
    images.emplace_back("img" + std::to_string(i) + ".jpg",
                        test::RandomDescriptors(300 + 10 * i, 6, 100 + i));
  }
  test::CreateDescriptorDatabase(path, images);
  VladOptions options;
  options.num_words = 8;
  options.dim = 16;  // capped at 8 - 1
  options.max_training_descriptors = 1000;
  options.num_threads = 1;
  const VladEmbedding one = TrainVladEmbedding({path}, options);
  options.num_threads = 3;
  const VladEmbedding three = TrainVladEmbedding({path}, options);
  EXPECT_EQ(one.Checksum(), three.Checksum());
  EXPECT_EQ(one.NumWords(), 8);
  EXPECT_EQ(one.OutputDim(), 7);
  options.seed = 1;
  EXPECT_NE(TrainVladEmbedding({path}, options).Checksum(), one.Checksum());
}

}  // namespace
}  // namespace colmap_gcn
