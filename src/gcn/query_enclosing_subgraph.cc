#include "gcn/query_enclosing_subgraph.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"
#include "util/option_check.h"

namespace colmap_gcn {

void QesOptions::Check() const {
  CHECK_OPTION_GE(k1, 1);
  CHECK_OPTION_GE(k2, 0);
  CHECK_OPTION_GE(u, 0);
}

int QesOptions::RequiredK() const { return std::max(k1, std::max(k2, u)); }

const char* GcnAggregationName(GcnAggregation aggregation) {
  switch (aggregation) {
    case GcnAggregation::kSymmetric:
      return "symmetric";
    case GcnAggregation::kRowNormalized:
      return "row";
  }
  return "unknown";
}

const EnumNames<GcnAggregation>& GcnAggregationNames() {
  static const EnumNames<GcnAggregation> names = {
      {"symmetric", GcnAggregation::kSymmetric},
      {"row", GcnAggregation::kRowNormalized}};
  return names;
}

std::vector<float> AggregationMatrix::RowSums() const {
  std::vector<float> sums(num_nodes, 0.f);
  for (int i = 0; i < num_nodes; ++i) {
    for (int e = offsets[i]; e < offsets[i + 1]; ++e) sums[i] += values[e];
  }
  return sums;
}

Eigen::MatrixXf AggregationMatrix::Dense() const {
  Eigen::MatrixXf dense = Eigen::MatrixXf::Zero(num_nodes, num_nodes);
  for (int i = 0; i < num_nodes; ++i) {
    for (int e = offsets[i]; e < offsets[i + 1]; ++e) {
      dense(i, columns[e]) = values[e];
    }
  }
  return dense;
}

AggregationMatrix ComputeAggregation(const QuerySubgraph& subgraph,
                                     GcnAggregation aggregation) {
  AggregationMatrix g;
  g.num_nodes = subgraph.NumNodes();
  g.offsets = subgraph.adjacency_offsets;
  g.columns = subgraph.adjacency;
  g.values.resize(g.columns.size());
  std::vector<float> inv_sqrt_degree(g.num_nodes, 0.f);
  for (int i = 0; i < g.num_nodes; ++i) {
    const int degree = subgraph.Degree(i);
    if (degree > 0) {
      inv_sqrt_degree[i] = 1.f / std::sqrt(static_cast<float>(degree));
    }
  }
  for (int i = 0; i < g.num_nodes; ++i) {
    const int degree = subgraph.Degree(i);
    for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
      if (aggregation == GcnAggregation::kSymmetric) {
        g.values[e] = inv_sqrt_degree[i] * inv_sqrt_degree[g.columns[e]];
      } else {
        g.values[e] = 1.f / static_cast<float>(degree);
      }
    }
  }
  return g;
}

QesBuilder::QesBuilder(const KnnGraph& knn, const QesOptions& options)
    : knn_(knn), options_(options), local_index_(knn.NumImages(), -1) {
  options_.Check();
  if (knn_.K() < options_.RequiredK()) {
    ThrowError("the kNN graph has ",
               knn_.K(),
               " neighbours per image but the QES needs max(k1, k2, u) = ",
               options_.RequiredK());
  }
}

void QesBuilder::Build(int query, QuerySubgraph* subgraph) {
  THROW_CHECK(query >= 0 && query < knn_.NumImages());
  QuerySubgraph& s = *subgraph;
  s.query = query;
  s.nodes.clear();
  s.adjacency_offsets.clear();
  s.adjacency.clear();

  // Stage 1: node discovery. The query is excluded by marking it.
  local_index_[query] = -2;
  auto add_node = [&](int index) {
    if (local_index_[index] == -1) {
      local_index_[index] = static_cast<int>(s.nodes.size());
      s.nodes.push_back(index);
    }
  };
  const int32_t* query_row = knn_.indices.data() + query * knn_.K();
  for (int i = 0; i < options_.k1; ++i) add_node(query_row[i]);
  s.num_one_hop = static_cast<int>(s.nodes.size());
  for (int i = 0; i < s.num_one_hop; ++i) {
    const int32_t* row = knn_.indices.data() + s.nodes[i] * knn_.K();
    for (int j = 0; j < options_.k2; ++j) add_node(row[j]);
  }

  // Stage 2: edges from every node to its u nearest neighbours inside V,
  // symmetrised. Collected as directed pairs, then sorted and deduplicated.
  const int n = s.NumNodes();
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<size_t>(2) * n * options_.u);
  for (int i = 0; i < n; ++i) {
    const int32_t* row = knn_.indices.data() + s.nodes[i] * knn_.K();
    for (int j = 0; j < options_.u; ++j) {
      const int other = local_index_[row[j]];
      if (other >= 0 && other != i) {
        edges.emplace_back(i, other);
        edges.emplace_back(other, i);
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  s.adjacency_offsets.assign(n + 1, 0);
  s.adjacency.reserve(edges.size());
  for (const auto& edge : edges) {
    ++s.adjacency_offsets[edge.first + 1];
    s.adjacency.push_back(edge.second);
  }
  for (int i = 0; i < n; ++i) {
    s.adjacency_offsets[i + 1] += s.adjacency_offsets[i];
  }

  // Reset the scratch map.
  local_index_[query] = -1;
  for (int index : s.nodes) local_index_[index] = -1;
}

QuerySubgraph BuildQuerySubgraph(const KnnGraph& knn,
                                 int query,
                                 const QesOptions& options) {
  QesBuilder builder(knn, options);
  QuerySubgraph subgraph;
  builder.Build(query, &subgraph);
  return subgraph;
}

const char* QesFeatureScalingName(QesFeatureScaling scaling) {
  switch (scaling) {
    case QesFeatureScaling::kNone:
      return "none";
    case QesFeatureScaling::kQueryScale:
      return "query";
  }
  return "unknown";
}

const EnumNames<QesFeatureScaling>& QesFeatureScalingNames() {
  static const EnumNames<QesFeatureScaling> names = {
      {"none", QesFeatureScaling::kNone},
      {"query", QesFeatureScaling::kQueryScale}};
  return names;
}

float QesFeatureFactor(const QuerySubgraph& subgraph,
                       const EmbeddingMatrix& embeddings,
                       QesFeatureScaling scaling) {
  if (scaling == QesFeatureScaling::kNone || subgraph.num_one_hop == 0) {
    return 1.f;
  }
  // In double, node by node in order: the same factor whatever the thread.
  double sum = 0;
  for (int i = 0; i < subgraph.num_one_hop; ++i) {
    sum += (embeddings.row(subgraph.nodes[i]) - embeddings.row(subgraph.query))
               .cast<double>()
               .squaredNorm();
  }
  const double mean_square =
      sum / (static_cast<double>(subgraph.num_one_hop) * embeddings.cols());
  if (!(mean_square > 1e-24)) return 1.f;
  return static_cast<float>(1.0 / std::sqrt(mean_square));
}

Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
QesFeatures(const QuerySubgraph& subgraph,
            const EmbeddingMatrix& embeddings,
            QesFeatureScaling scaling) {
  const int n = subgraph.NumNodes();
  const float factor = QesFeatureFactor(subgraph, embeddings, scaling);
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> x(
      n, embeddings.cols());
  for (int i = 0; i < n; ++i) {
    x.row(i) =
        embeddings.row(subgraph.nodes[i]) - embeddings.row(subgraph.query);
  }
  if (factor != 1.f) x *= factor;
  return x;
}

QesOptions CapQesOptions(const QesOptions& qes, int num_images) {
  QesOptions capped = qes;
  const int max_k = std::max(num_images - 1, 0);
  capped.k1 = std::min(capped.k1, max_k);
  capped.k2 = std::min(capped.k2, max_k);
  capped.u = std::min(capped.u, max_k);
  return capped;
}

KnnGraph ComputeKnnForQes(const EmbeddingMatrix& embeddings,
                          const QesOptions& qes,
                          int num_threads) {
  KnnOptions knn_options;
  knn_options.k = std::min(
      qes.RequiredK(), std::max(static_cast<int>(embeddings.rows()) - 1, 1));
  knn_options.num_threads = num_threads;
  return ComputeExactKnn(embeddings, knn_options);
}

}  // namespace colmap_gcn
