#include "retrieval/knn.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "test_utils.h"
#include "util/error.h"
#include "util/option_check.h"

namespace colmap_gcn {
namespace {

struct Reference {
  std::vector<std::vector<int>> indices;
  std::vector<std::vector<double>> similarities;
};

// Per-query brute force in double with the documented order.
Reference BruteForce(const EmbeddingMatrix& x, int k) {
  const int n = static_cast<int>(x.rows());
  Reference reference;
  for (int i = 0; i < n; ++i) {
    std::vector<std::pair<double, int>> all;
    for (int j = 0; j < n; ++j) {
      if (j == i) continue;
      all.emplace_back(x.row(i).cast<double>().dot(x.row(j).cast<double>()), j);
    }
    std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) {
      return a.first > b.first || (a.first == b.first && a.second < b.second);
    });
    all.resize(std::min<int>(k, all.size()));
    reference.indices.emplace_back();
    reference.similarities.emplace_back();
    for (const auto& [similarity, j] : all) {
      reference.indices.back().push_back(j);
      reference.similarities.back().push_back(similarity);
    }
  }
  return reference;
}

// Small integers: every dot product is exact in float, so ties are exact
// and GEMM must agree with brute force bit for bit.
EmbeddingMatrix IntegerData(int n, int d, uint32_t seed) {
  std::mt19937 rng(seed);
  EmbeddingMatrix x(n, d);
  for (int i = 0; i < x.size(); ++i) {
    x.data()[i] = static_cast<float>(static_cast<int>(rng() % 5) - 2);
  }
  return x;
}

void ExpectExactlyEqual(const KnnGraph& graph, const Reference& reference) {
  ASSERT_EQ(graph.NumImages(), static_cast<int>(reference.indices.size()));
  for (int i = 0; i < graph.NumImages(); ++i) {
    ASSERT_EQ(graph.K(), static_cast<int>(reference.indices[i].size()));
    for (int n = 0; n < graph.K(); ++n) {
      EXPECT_EQ(graph.indices(i, n), reference.indices[i][n])
          << "row " << i << " rank " << n;
      EXPECT_EQ(graph.similarities(i, n), reference.similarities[i][n]);
    }
  }
}

bool Identical(const KnnGraph& a, const KnnGraph& b) {
  return a.indices == b.indices && a.similarities == b.similarities;
}

TEST(ExactKnn, EqualsBruteForceWithExactTiesForAnyThreadsAndBlocks) {
  const EmbeddingMatrix x = IntegerData(301, 6, 1);  // many exact ties
  const Reference reference = BruteForce(x, 12);
  KnnOptions options;
  options.k = 12;
  options.block_size = 32;  // 10 blocks, the last partial
  const KnnGraph first = ComputeExactKnn(x, options);
  ExpectExactlyEqual(first, reference);
  for (const int threads : {1, 2, 3, 7}) {
    for (const int block_size : {32, 1024}) {
      options.num_threads = threads;
      options.block_size = block_size;
      const KnnGraph graph = ComputeExactKnn(x, options);
      ExpectExactlyEqual(graph, reference);
      if (block_size == 32) {
        EXPECT_TRUE(Identical(graph, first)) << threads << " threads";
      }
    }
  }
}

TEST(ExactKnn, MatchesBruteForceOnRandomUnitVectors) {
  std::mt19937 rng(3);
  std::normal_distribution<float> normal;
  EmbeddingMatrix x(500, 64);
  for (int i = 0; i < x.size(); ++i) x.data()[i] = normal(rng);
  x.rowwise().normalize();
  const Reference reference = BruteForce(x, 20);
  KnnOptions options;
  options.k = 20;
  options.block_size = 64;
  options.num_threads = 2;
  const KnnGraph graph = ComputeExactKnn(x, options);
  ASSERT_EQ(graph.K(), 20);
  for (int i = 0; i < graph.NumImages(); ++i) {
    for (int n = 0; n < graph.K(); ++n) {
      // Float GEMM vs double: equal up to rounding; indices may only differ
      // where the true similarities are within rounding of each other.
      EXPECT_NEAR(graph.similarities(i, n), reference.similarities[i][n], 1e-5);
      const int j = graph.indices(i, n);
      EXPECT_NE(j, i);
      EXPECT_NEAR(x.row(i).cast<double>().dot(x.row(j).cast<double>()),
                  reference.similarities[i][n],
                  1e-5);
      if (n > 0) {
        EXPECT_GE(graph.similarities(i, n - 1), graph.similarities(i, n));
      }
    }
  }
  options.num_threads = 1;
  EXPECT_TRUE(Identical(ComputeExactKnn(x, options), graph));
}

TEST(ExactKnn, FewerImagesThanKListsAllOthers) {
  const EmbeddingMatrix x = IntegerData(5, 4, 2);
  KnnOptions options;
  options.k = 100;
  const KnnGraph graph = ComputeExactKnn(x, options);
  EXPECT_EQ(graph.K(), 4);
  ExpectExactlyEqual(graph, BruteForce(x, 100));
}

TEST(ExactKnn, DuplicateVectorsFindEachOtherAndTieByIndex) {
  EmbeddingMatrix x(6, 3);
  x.setConstant(0.5f);
  KnnOptions options;
  options.k = 3;
  options.block_size = 4;
  const KnnGraph graph = ComputeExactKnn(x, options);
  ASSERT_EQ(graph.K(), 3);
  for (int i = 0; i < 6; ++i) {
    std::vector<int> expected;
    for (int j = 0; j < 6 && expected.size() < 3; ++j) {
      if (j != i) expected.push_back(j);
    }
    for (int n = 0; n < 3; ++n) {
      EXPECT_EQ(graph.indices(i, n), expected[n]);
      EXPECT_FLOAT_EQ(graph.similarities(i, n), 0.75f);
    }
  }
}

TEST(ExactKnn, SymmetricSimilarities) {
  const EmbeddingMatrix x = IntegerData(40, 5, 9);
  KnnOptions options;
  options.k = 39;
  options.block_size = 7;
  const KnnGraph graph = ComputeExactKnn(x, options);
  std::vector<std::vector<float>> s(40, std::vector<float>(40, 0));
  for (int i = 0; i < 40; ++i) {
    for (int n = 0; n < 39; ++n)
      s[i][graph.indices(i, n)] = graph.similarities(i, n);
  }
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 40; ++j) EXPECT_EQ(s[i][j], s[j][i]);
  }
}

TEST(ExactKnn, OneOrNoImageGivesEmptyRows) {
  KnnOptions options;
  const KnnGraph one = ComputeExactKnn(EmbeddingMatrix::Ones(1, 8), options);
  EXPECT_EQ(one.NumImages(), 1);
  EXPECT_EQ(one.K(), 0);
  const KnnGraph none = ComputeExactKnn(EmbeddingMatrix(0, 8), options);
  EXPECT_EQ(none.NumImages(), 0);
  options.k = 0;
  EXPECT_EQ(ComputeExactKnn(IntegerData(4, 3, 1), options).K(), 0);
}

TEST(ExactKnn, RejectsNonFiniteInputAndBadOptions) {
  EmbeddingMatrix x = EmbeddingMatrix::Ones(3, 2);
  x(1, 1) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(ComputeExactKnn(x, KnnOptions()), Error);
  KnnOptions options;
  options.block_size = 0;
  EXPECT_THROW(ComputeExactKnn(EmbeddingMatrix::Ones(3, 2), options), Error);
  EXPECT_EQ(ParseEnum(KnnMethodNames(), "faiss_hnsw", "method"),
            KnnMethod::kFaissHnsw);
  test::ExpectErrorContaining(
      [] { ParseEnum(KnnMethodNames(), "annoy", "--method"); },
      "--method must be one of exact|faiss_hnsw (got \"annoy\")");
}

TEST(ApproximateKnn, FindsNearNeighboursWhenAvailable) {
  if (!FaissAvailable()) {
    EXPECT_THROW(ComputeApproximateKnn(IntegerData(10, 4, 1), KnnOptions()),
                 Error);
    GTEST_SKIP() << "built without FAISS";
  }
  std::mt19937 rng(5);
  std::normal_distribution<float> normal;
  EmbeddingMatrix x(400, 32);
  for (int i = 0; i < x.size(); ++i) x.data()[i] = normal(rng);
  x.rowwise().normalize();
  KnnOptions options;
  options.k = 10;
  options.method = KnnMethod::kFaissHnsw;
  options.num_threads = 1;
  const KnnGraph approximate = ComputeKnn(x, options);
  options.method = KnnMethod::kExact;
  const KnnGraph exact = ComputeKnn(x, options);
  ASSERT_EQ(approximate.K(), 10);
  int found = 0;
  for (int i = 0; i < x.rows(); ++i) {
    for (int n = 0; n < 10; ++n) {
      EXPECT_NE(approximate.indices(i, n), i);
      for (int m = 0; m < 10; ++m) {
        found += approximate.indices(i, n) == exact.indices(i, m);
      }
    }
  }
  EXPECT_GT(found, 0.9 * 400 * 10);  // recall@10 of HNSW on easy data
}

}  // namespace
}  // namespace colmap_gcn
