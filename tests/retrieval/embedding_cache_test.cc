#include "retrieval/embedding_cache.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "retrieval/global_descriptors.h"
#include "retrieval_test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

class EmbeddingCacheTest : public testing::Test {
 protected:
  void SetUp() override {
    path_ = JoinPaths(dir_.Path(), "db.db");
    test::CreateRandomDescriptorDatabase(path_, 6, 200, 5, 40, "img");
    VladOptions options;
    options.num_words = 4;
    options.dim = 3;
    const Database database(path_);
    model_ = TrainVladEmbedding({&database}, options, 1.0);
  }

  TemporaryDirectory dir_;
  std::string path_;
  VladEmbedding model_;
};

TEST_F(EmbeddingCacheTest, UnchangedDatabaseHitsTheCache) {
  const std::string cache = DefaultEmbeddingCachePath(path_);
  std::vector<image_t> ids1, ids2;
  EmbeddingCacheStats stats;
  const EmbeddingMatrix first = ComputeDatabaseEmbeddings(
      Database(path_), model_, &ids1, cache, 2, &stats);
  EXPECT_EQ(stats.num_computed, 6u);
  EXPECT_EQ(stats.num_cached, 0u);
  ASSERT_TRUE(ExistsFile(cache));
  const EmbeddingMatrix second = ComputeDatabaseEmbeddings(
      Database(path_), model_, &ids2, cache, 1, &stats);
  EXPECT_EQ(stats.num_cached, 6u);
  EXPECT_EQ(stats.num_computed, 0u);
  EXPECT_EQ(first, second);
  EXPECT_EQ(ids1, ids2);
  EXPECT_EQ(ids1, (std::vector<image_t>{1, 2, 3, 4, 5, 6}));
  // Without a cache the same numbers come out.
  EXPECT_EQ(ComputeDatabaseEmbeddings(Database(path_), model_, &ids2), first);
}

TEST_F(EmbeddingCacheTest, ChangedDescriptorsInACopyMissForThatImageOnly) {
  std::vector<image_t> ids;
  const EmbeddingMatrix original = ComputeDatabaseEmbeddings(
      Database(path_), model_, &ids, DefaultEmbeddingCachePath(path_));
  const std::string copy = JoinPaths(dir_.Path(), "copy.db");
  std::filesystem::copy_file(path_, copy);
  std::filesystem::copy_file(DefaultEmbeddingCachePath(path_),
                             DefaultEmbeddingCachePath(copy));
  // Same number of descriptors, different content: an image-count or
  // row-count key would miss this.
  test::UpdateDescriptors(copy, 3, test::RandomDescriptors(200, 5, 999));
  EmbeddingCacheStats stats;
  const EmbeddingMatrix changed = ComputeDatabaseEmbeddings(
      Database(copy), model_, &ids, DefaultEmbeddingCachePath(copy), 2, &stats);
  EXPECT_EQ(stats.num_computed, 1u);
  EXPECT_EQ(stats.num_cached, 5u);
  EXPECT_NE(changed.row(2), original.row(2));
  for (int i : {0, 1, 3, 4, 5}) EXPECT_EQ(changed.row(i), original.row(i));
  // And the result equals an uncached computation.
  EXPECT_EQ(ComputeDatabaseEmbeddings(Database(copy), model_, &ids), changed);
}

TEST_F(EmbeddingCacheTest, OtherModelOrCorruptCacheRecomputes) {
  const std::string cache = DefaultEmbeddingCachePath(path_);
  std::vector<image_t> ids;
  ComputeDatabaseEmbeddings(Database(path_), model_, &ids, cache);
  VladOptions options;
  options.num_words = 4;
  options.dim = 3;
  options.seed = 5;
  const Database database(path_);
  const VladEmbedding other = TrainVladEmbedding({&database}, options, 1.0);
  ASSERT_NE(other.Checksum(), model_.Checksum());
  EmbeddingCacheStats stats;
  ComputeDatabaseEmbeddings(database, other, &ids, cache, 1, &stats);
  EXPECT_EQ(stats.num_computed, 6u);
  std::string bytes = ReadTextFile(cache);
  bytes[bytes.size() / 2] ^= 1;
  WriteFileAtomically(cache, bytes);
  ComputeDatabaseEmbeddings(database, other, &ids, cache, 1, &stats);
  EXPECT_EQ(stats.num_computed, 6u);
}

TEST_F(EmbeddingCacheTest, SelfTrainedModelIsCachedAndRetrainedOnChange) {
  GlobalDescriptorOptions options;
  options.vlad.num_words = 4;
  options.vlad.dim = 8;
  std::vector<image_t> ids;
  const EmbeddingMatrix first =
      ComputeGlobalDescriptors(Database(path_), options, &ids);
  EXPECT_EQ(first.cols(), 5);  // N - 1
  ASSERT_TRUE(ExistsFile(SelfTrainedModelPath(path_)));
  const uint64_t checksum =
      VladEmbedding::Read(SelfTrainedModelPath(path_)).Checksum();
  EXPECT_EQ(ComputeGlobalDescriptors(Database(path_), options, &ids), first);
  test::UpdateDescriptors(path_, 2, test::RandomDescriptors(150, 5, 7));
  ComputeGlobalDescriptors(Database(path_), options, &ids);
  EXPECT_NE(VladEmbedding::Read(SelfTrainedModelPath(path_)).Checksum(),
            checksum);
  for (int i = 0; i < first.rows(); ++i) {
    EXPECT_NEAR(first.row(i).norm(), 1.0, 1e-5);
  }
}

// The embedding runs in worker threads: a failure there (a codebook for
// another descriptor size) must reach the caller as an Error for every
// thread count, with no cache written.
TEST_F(EmbeddingCacheTest, WorkerErrorsReachTheCaller) {
  const int kWords = 2;
  const int kDim = 64;
  PcaWhitening pca;
  pca.mean = Eigen::RowVectorXf::Zero(kWords * kDim);
  pca.projection = FloatMatrix::Identity(3, kWords * kDim);
  pca.eigenvalues = Eigen::VectorXf::Ones(3);
  const VladEmbedding wrong(FloatMatrix::Ones(kWords, kDim), pca);
  const std::string cache = JoinPaths(dir_.Path(), "wrong.cache");
  for (int num_threads : {1, 2, 4}) {
    std::vector<image_t> ids;
    try {
      ComputeDatabaseEmbeddings(
          Database(path_), wrong, &ids, cache, num_threads);
      FAIL() << "no error with " << num_threads << " threads";
    } catch (const Error& error) {
      EXPECT_EQ(std::string(error.what()),
                "descriptors have 128 columns, the VLAD codebook 64");
    }
    EXPECT_FALSE(ExistsFile(cache));
  }
}

}  // namespace
}  // namespace colmap_gcn
