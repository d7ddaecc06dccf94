#include "training/gcn_network.h"

#include <algorithm>
#include <cmath>

#include "math/sgemm.h"
#include "util/error.h"

namespace colmap_gcn {
namespace {

template <typename T>
struct View {
  const T* data;
  int rows;
  int cols;
  long row_stride;
  long col_stride;
  View Transposed() const { return {data, cols, rows, col_stride, row_stride}; }
};

template <typename Derived>
View<typename Derived::Scalar> ViewOf(const Eigen::MatrixBase<Derived>& m) {
  static_assert(Derived::IsRowMajor || Derived::ColsAtCompileTime == 1,
                "row-major only");
  return {m.derived().data(),
          static_cast<int>(m.rows()),
          static_cast<int>(m.cols()),
          static_cast<long>(m.outerStride()),
          1};
}

// C = A B + beta C, C row-major with leading dimension ldc.
void Gemm(const View<float>& a,
          const View<float>& b,
          float beta,
          float* c,
          long ldc) {
  Sgemm({a.data, a.rows, a.cols, a.row_stride, a.col_stride},
        {b.data, b.rows, b.cols, b.row_stride, b.col_stride},
        beta,
        c,
        ldc);
}

void Gemm(const View<double>& a,
          const View<double>& b,
          double beta,
          double* c,
          long ldc) {
  typedef Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic> Stride;
  Eigen::Map<const RowMatrix<double>, 0, Stride> am(
      a.data, a.rows, a.cols, Stride(a.row_stride, a.col_stride));
  Eigen::Map<const RowMatrix<double>, 0, Stride> bm(
      b.data, b.rows, b.cols, Stride(b.row_stride, b.col_stride));
  Eigen::Map<RowMatrix<double>, 0, Eigen::OuterStride<>> cm(
      c, a.rows, b.cols, Eigen::OuterStride<>(ldc));
  if (beta == 0.0) {
    cm.noalias() = am * bm;
  } else {
    cm *= beta;
    cm.noalias() += am * bm;
  }
}

// out[0:rows] (+)= G[0:rows, :] h (sparse rows of G).
template <typename T>
void Aggregate(const AggregationMatrix& g,
               const T* h,
               int dim,
               long h_stride,
               int rows,
               T* out,
               long out_stride) {
  for (int i = 0; i < rows; ++i) {
    T* out_row = out + i * out_stride;
    std::fill(out_row, out_row + dim, T(0));
    for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
      const T w = static_cast<T>(g.values[e]);
      const T* in_row = h + g.columns[e] * h_stride;
      for (int j = 0; j < dim; ++j) out_row[j] += w * in_row[j];
    }
  }
}

template <typename T>
T Softplus(T z) {
  return std::max(z, T(0)) + std::log1p(std::exp(-std::abs(z)));
}

template <typename T>
T Sigmoid(T z) {
  if (z >= 0) return T(1) / (T(1) + std::exp(-z));
  const T e = std::exp(z);
  return e / (T(1) + e);
}

}  // namespace

GcnGraph<float> MakeGcnGraph(const GcnModel& model,
                             const QuerySubgraph& subgraph,
                             const EmbeddingMatrix& embeddings) {
  GcnGraph<float> graph;
  graph.features = model.NodeFeatures(subgraph, embeddings);
  graph.aggregation = ComputeAggregation(subgraph, model.aggregation);
  graph.num_one_hop = subgraph.num_one_hop;
  return graph;
}

template <typename T>
ColVector<T> GcnForwardReference(const GcnParameters<T>& params,
                                 const GcnGraph<T>& graph) {
  const GcnShape& shape = params.Shape();
  THROW_CHECK(graph.features.cols() == shape.input_dim);
  const int n = static_cast<int>(graph.features.rows());
  const RowMatrix<T> g = graph.aggregation.Dense().template cast<T>();
  RowMatrix<T> h = graph.features;
  for (int l = 0; l < shape.NumGcnLayers(); ++l) {
    RowMatrix<T> cat(n, 2 * h.cols());
    cat << h, g * h;
    RowMatrix<T> z = cat * params.GcnWeight(l);
    z.rowwise() += params.GcnBias(l).transpose();
    h = z.cwiseMax(T(0));
  }
  const int n1 = graph.num_one_hop;
  RowMatrix<T> u = h.topRows(n1) * params.Fc1Weight();
  u.rowwise() += params.Fc1Bias().transpose();
  RowMatrix<T> v(n1, shape.fc_dim);
  for (int i = 0; i < n1; ++i) {
    for (int j = 0; j < shape.fc_dim; ++j) {
      v(i, j) = u(i, j) > 0 ? u(i, j) : params.Prelu()(j) * u(i, j);
    }
  }
  ColVector<T> logits = v * params.Fc2Weight();
  logits.array() += params.Fc2Bias();
  return logits;
}

namespace {

// What the backward pass needs of the forward pass: per GCN layer the input
// [H || G H] and the pre-activations (the last layer on the 1-hop rows
// only), the FC1 output before and after the PReLU, and the logits.
template <typename T>
struct ForwardCache {
  std::vector<RowMatrix<T>> cats;
  std::vector<RowMatrix<T>> pre;
  std::vector<RowMatrix<T>> hs;
  RowMatrix<T> u;
  RowMatrix<T> v;
  ColVector<T> logits;
};

template <typename T>
void ForwardWithCache(const GcnParameters<T>& params,
                      const GcnGraph<T>& graph,
                      ForwardCache<T>* cache) {
  const GcnShape& shape = params.Shape();
  const int num_layers = shape.NumGcnLayers();
  const int n = static_cast<int>(graph.features.rows());
  const int n1 = graph.num_one_hop;
  cache->cats.resize(num_layers);
  cache->pre.resize(num_layers);
  cache->hs.resize(num_layers);
  const RowMatrix<T>* h = &graph.features;
  for (int l = 0; l < num_layers; ++l) {
    const int in = shape.LayerInputDim(l);
    const int out = shape.gcn_dims[l];
    const int rows = (l == num_layers - 1) ? n1 : n;
    RowMatrix<T>& cat = cache->cats[l];
    cat.resize(rows, 2 * in);
    cat.leftCols(in) = h->topRows(rows);
    Aggregate(
        graph.aggregation, h->data(), in, in, rows, cat.data() + in, 2 * in);
    RowMatrix<T>& z = cache->pre[l];
    z.resize(rows, out);
    for (int i = 0; i < rows; ++i) z.row(i) = params.GcnBias(l).transpose();
    Gemm(ViewOf(cat), ViewOf(params.GcnWeight(l)), T(1), z.data(), out);
    cache->hs[l] = z.cwiseMax(T(0));
    h = &cache->hs[l];
  }
  const RowMatrix<T>& h_last = cache->hs[num_layers - 1];  // n1 x d_L
  RowMatrix<T>& u = cache->u;
  u.resize(n1, shape.fc_dim);
  for (int i = 0; i < n1; ++i) u.row(i) = params.Fc1Bias().transpose();
  Gemm(
      ViewOf(h_last), ViewOf(params.Fc1Weight()), T(1), u.data(), shape.fc_dim);
  RowMatrix<T>& v = cache->v;
  v.resize(n1, shape.fc_dim);
  for (int i = 0; i < n1; ++i) {
    for (int j = 0; j < shape.fc_dim; ++j) {
      v(i, j) = u(i, j) > 0 ? u(i, j) : params.Prelu()(j) * u(i, j);
    }
  }
  cache->logits = v * params.Fc2Weight();
  cache->logits.array() += params.Fc2Bias();
}

// dH_prev of GCN layer l from the gradient of its pre-activations:
// dcat[:, :in] (top rows) + G[0:rows,:]^T dcat[:, in:].
template <typename T>
RowMatrix<T> LayerInputGradient(const GcnParameters<T>& params,
                                const AggregationMatrix& g,
                                int l,
                                int n,
                                const RowMatrix<T>& dpre) {
  const int in = params.Shape().LayerInputDim(l);
  const int rows = static_cast<int>(dpre.rows());
  RowMatrix<T> dcat(rows, 2 * in);
  Gemm(ViewOf(dpre),
       ViewOf(params.GcnWeight(l)).Transposed(),
       T(0),
       dcat.data(),
       2 * in);
  RowMatrix<T> dh_prev = RowMatrix<T>::Zero(n, in);
  dh_prev.topRows(rows) = dcat.leftCols(in);
  for (int i = 0; i < rows; ++i) {
    const T* src = dcat.data() + i * 2 * in + in;
    for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
      const T w = static_cast<T>(g.values[e]);
      T* dst = dh_prev.data() + static_cast<long>(g.columns[e]) * in;
      for (int j = 0; j < in; ++j) dst[j] += w * src[j];
    }
  }
  return dh_prev;
}

// Adds d(loss)/d(params) to *gradient given dz = d(loss)/d(logits).
template <typename T>
void Backward(const GcnParameters<T>& params,
              const GcnGraph<T>& graph,
              const ForwardCache<T>& cache,
              const ColVector<T>& dz,
              GcnParameters<T>* gradient) {
  const GcnShape& shape = params.Shape();
  const int num_layers = shape.NumGcnLayers();
  const int n = static_cast<int>(graph.features.rows());
  const int n1 = graph.num_one_hop;
  const RowMatrix<T>& u = cache.u;
  const RowMatrix<T>& h_last = cache.hs[num_layers - 1];
  GcnParameters<T>& grad = *gradient;

  // FC2.
  grad.Fc2Weight().noalias() += cache.v.transpose() * dz;
  grad.Fc2Bias() += dz.sum();
  RowMatrix<T> du = dz * params.Fc2Weight().transpose();  // dV, n1 x fc
  // PReLU.
  for (int i = 0; i < n1; ++i) {
    for (int j = 0; j < shape.fc_dim; ++j) {
      if (u(i, j) > 0) continue;
      grad.Prelu()(j) += du(i, j) * u(i, j);
      du(i, j) *= params.Prelu()(j);
    }
  }
  // FC1.
  {
    auto gw = grad.Fc1Weight();
    Gemm(ViewOf(h_last).Transposed(), ViewOf(du), T(1), gw.data(), gw.cols());
    grad.Fc1Bias() += du.colwise().sum().transpose();
  }
  RowMatrix<T> dh(n1, shape.gcn_dims.back());
  Gemm(ViewOf(du),
       ViewOf(params.Fc1Weight()).Transposed(),
       T(0),
       dh.data(),
       dh.cols());

  // GCN layers, last to first.
  for (int l = num_layers - 1; l >= 0; --l) {
    const int out = shape.gcn_dims[l];
    RowMatrix<T> dpre = (cache.pre[l].array() > T(0)).select(dh, T(0));
    auto gw = grad.GcnWeight(l);
    Gemm(
        ViewOf(cache.cats[l]).Transposed(), ViewOf(dpre), T(1), gw.data(), out);
    grad.GcnBias(l) += dpre.colwise().sum().transpose();
    if (l == 0) break;
    dh = LayerInputGradient(params, graph.aggregation, l, n, dpre);
  }
}

}  // namespace

template <typename T>
T GcnLossAndGradient(const GcnParameters<T>& params,
                     const GcnGraph<T>& graph,
                     T positive_weight,
                     GcnParameters<T>* gradient,
                     ColVector<T>* logits_out) {
  const GcnShape& shape = params.Shape();
  const int n = static_cast<int>(graph.features.rows());
  const int n1 = graph.num_one_hop;
  THROW_CHECK(graph.features.cols() == shape.input_dim);
  THROW_CHECK(graph.aggregation.num_nodes == n);
  THROW_CHECK(n1 <= n);
  const bool with_labels = !graph.labels.empty() || gradient != nullptr;
  if (with_labels) THROW_CHECK(static_cast<int>(graph.labels.size()) == n1);

  ForwardCache<T> cache;
  ForwardWithCache(params, graph, &cache);
  const ColVector<T>& logits = cache.logits;
  if (logits_out != nullptr) *logits_out = logits;
  if (!with_labels) return T(0);

  // Loss and dL/dz.
  T loss = 0;
  ColVector<T> dz(n1);
  for (int i = 0; i < n1; ++i) {
    const T y = graph.labels[i] ? T(1) : T(0);
    const T w = graph.labels[i] ? positive_weight : T(1);
    loss += w * (Softplus(logits(i)) - y * logits(i));
    dz(i) = w * (Sigmoid(logits(i)) - y);
  }
  if (gradient != nullptr) Backward(params, graph, cache, dz, gradient);
  return loss;
}

template ColVector<float> GcnForwardReference(const GcnParameters<float>&,
                                              const GcnGraph<float>&);
template ColVector<double> GcnForwardReference(const GcnParameters<double>&,
                                               const GcnGraph<double>&);
template float GcnLossAndGradient(const GcnParameters<float>&,
                                  const GcnGraph<float>&,
                                  float,
                                  GcnParameters<float>*,
                                  ColVector<float>*);
template double GcnLossAndGradient(const GcnParameters<double>&,
                                   const GcnGraph<double>&,
                                   double,
                                   GcnParameters<double>*,
                                   ColVector<double>*);

}  // namespace colmap_gcn
