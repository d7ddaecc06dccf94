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

QesBuilder::QesBuilder(const KnnGraph& knn,
                       const QesOptions& options,
                       QesStructureFeatures structure)
    : knn_(knn),
      options_(options),
      reciprocal_(QesStructureDim(structure) > 0),
      local_index_(knn.NumImages(), -1),
      near_query_(reciprocal_ ? knn.NumImages() : 0, 0) {
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
  s.reciprocal.clear();

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

  if (reciprocal_) ComputeReciprocalFeatures(&s);

  // Reset the scratch map.
  local_index_[query] = -1;
  for (int index : s.nodes) local_index_[index] = -1;
}

void QesBuilder::ComputeReciprocalFeatures(QuerySubgraph* subgraph) {
  QuerySubgraph& s = *subgraph;
  const int k = knn_.K();
  const int query = s.query;
  const int32_t* query_row = knn_.indices.data() + query * k;
  constexpr int kSmall = 5;
  constexpr int kLarge = 10;
  const int small = std::min(kSmall, k);
  const int large = std::min(kLarge, k);
  // Bit 1: in {q} + small nearest of q; bit 2: in {q} + large nearest.
  near_query_[query] = 3;
  for (int j = 0; j < large; ++j)
    near_query_[query_row[j]] |= j < small ? 3 : 2;
  const float log_k = std::log(1.f + static_cast<float>(k));
  auto rank_of = [k](const int32_t* row, int index) {
    for (int j = 0; j < k; ++j) {
      if (row[j] == index) return j;
    }
    return k;
  };
  const int n = s.NumNodes();
  s.reciprocal.resize(static_cast<size_t>(n) * kQesReciprocalDim);
  for (int i = 0; i < n; ++i) {
    const int node = s.nodes[i];
    const int32_t* row = knn_.indices.data() + node * k;
    // Overlaps of {q} + nearest of q with {v} + nearest of v.
    int common_small = (near_query_[node] & 1) ? 1 : 0;
    int common_large = (near_query_[node] & 2) ? 1 : 0;
    for (int j = 0; j < large; ++j) {
      if (j < small && (near_query_[row[j]] & 1)) ++common_small;
      if (near_query_[row[j]] & 2) ++common_large;
    }
    float* out =
        s.reciprocal.data() + static_cast<size_t>(i) * kQesReciprocalDim;
    out[0] =
        std::log(1.f + static_cast<float>(rank_of(query_row, node))) / log_k;
    out[1] = std::log(1.f + static_cast<float>(rank_of(row, query))) / log_k;
    out[2] = static_cast<float>(common_small) /
             static_cast<float>(2 * (small + 1) - common_small);
    out[3] = static_cast<float>(common_large) /
             static_cast<float>(2 * (large + 1) - common_large);
  }
  near_query_[query] = 0;
  for (int j = 0; j < large; ++j) near_query_[query_row[j]] = 0;
}

QuerySubgraph BuildQuerySubgraph(const KnnGraph& knn,
                                 int query,
                                 const QesOptions& options,
                                 QesStructureFeatures structure) {
  QesBuilder builder(knn, options, structure);
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

const char* QesStructureFeaturesName(QesStructureFeatures features) {
  switch (features) {
    case QesStructureFeatures::kNone:
      return "none";
    case QesStructureFeatures::kReciprocal:
      return "reciprocal";
    case QesStructureFeatures::kReciprocalOnly:
      return "reciprocal_only";
  }
  return "unknown";
}

const EnumNames<QesStructureFeatures>& QesStructureFeaturesNames() {
  static const EnumNames<QesStructureFeatures> names = {
      {"none", QesStructureFeatures::kNone},
      {"reciprocal", QesStructureFeatures::kReciprocal},
      {"reciprocal_only", QesStructureFeatures::kReciprocalOnly}};
  return names;
}

int QesStructureDim(QesStructureFeatures features) {
  switch (features) {
    case QesStructureFeatures::kNone:
      return 0;
    case QesStructureFeatures::kReciprocal:
      return kQesReciprocalDim;
    case QesStructureFeatures::kReciprocalOnly:
      return kQesReciprocalDim + 1;
  }
  return 0;
}

bool QesUsesEmbeddingDifferences(QesStructureFeatures features) {
  return features != QesStructureFeatures::kReciprocalOnly;
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

Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
QesStructureValues(const QuerySubgraph& subgraph,
                   const EmbeddingMatrix& embeddings,
                   QesFeatureScaling scaling,
                   QesStructureFeatures structure) {
  const int n = subgraph.NumNodes();
  const int dim = QesStructureDim(structure);
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> x(n,
                                                                          dim);
  if (dim == 0) return x;
  THROW_CHECK(subgraph.reciprocal.size() ==
              static_cast<size_t>(n) * kQesReciprocalDim);
  int column = 0;
  if (structure == QesStructureFeatures::kReciprocalOnly) {
    const float factor = QesFeatureFactor(subgraph, embeddings, scaling) /
                         std::sqrt(static_cast<float>(embeddings.cols()));
    for (int i = 0; i < n; ++i) {
      x(i, 0) = factor * (embeddings.row(subgraph.nodes[i]) -
                          embeddings.row(subgraph.query))
                             .norm();
    }
    column = 1;
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < kQesReciprocalDim; ++j) {
      x(i, column + j) =
          subgraph.reciprocal[static_cast<size_t>(i) * kQesReciprocalDim + j];
    }
  }
  return x;
}

Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
QesNodeFeatures(const QuerySubgraph& subgraph,
                const EmbeddingMatrix& embeddings,
                QesFeatureScaling scaling,
                QesStructureFeatures structure) {
  if (structure == QesStructureFeatures::kNone) {
    return QesFeatures(subgraph, embeddings, scaling);
  }
  const auto values =
      QesStructureValues(subgraph, embeddings, scaling, structure);
  if (!QesUsesEmbeddingDifferences(structure)) return values;
  const int d = static_cast<int>(embeddings.cols());
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> x(
      subgraph.NumNodes(), d + values.cols());
  x.leftCols(d) = QesFeatures(subgraph, embeddings, scaling);
  x.rightCols(values.cols()) = values;
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
