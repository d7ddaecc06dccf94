#include "gcn/gcn_inference.h"

#include <algorithm>
#include <cmath>

#include "math/sgemm.h"
#include "util/error.h"
#include "util/logging.h"
#include "util/threading.h"

namespace colmap_gcn {
namespace {

float Sigmoid(float z) {
  if (z >= 0) return 1.f / (1.f + std::exp(-z));
  const float e = std::exp(z);
  return e / (1.f + e);
}

void EnsureSize(std::vector<float>* buffer, size_t size) {
  if (buffer->size() < size) buffer->resize(size);
}

}  // namespace

GcnScorer::GcnScorer(const GcnModel& model,
                     const EmbeddingMatrix& embeddings,
                     int num_threads)
    : model_(model), embeddings_(embeddings) {
  model_.Check();
  model_.CheckEmbeddingDimension(static_cast<int>(embeddings.cols()));
  const int d = model_.DifferenceDim();
  const int input_dim = model_.shape.input_dim;
  const int h1 = model_.shape.gcn_dims[0];
  const auto w1 = model_.params.GcnWeight(0);  // 2 input_dim x h1
  // The embedding rows of W1 reshaped to d x 2h1: [W_self | W_agg], rows
  // scaled by s.
  RowMatrix<float> w(d, 2 * h1);
  w.leftCols(h1) = w1.topRows(d);
  w.rightCols(h1) = w1.middleRows(input_dim, d);
  offset_ = (model_.input_shift.head(d)
                 .cwiseProduct(model_.input_scale.head(d))
                 .transpose() *
             w)
                .transpose();
  for (int i = 0; i < d; ++i) w.row(i) *= model_.input_scale(i);
  // The structural rows stay per node: [W_self | W_agg] of those inputs.
  const int extra = input_dim - d;
  structure_weight_.resize(extra, 2 * h1);
  structure_weight_.leftCols(h1) = w1.middleRows(d, extra);
  structure_weight_.rightCols(h1) = w1.middleRows(input_dim + d, extra);
  const long n = embeddings.rows();
  // Nothing to project when the model reads no embedding differences.
  if (d > 0) projected_.resize(n, 2 * h1);
  // In row blocks so that large collections can be projected in parallel.
  constexpr int kBlock = 4096;
  const int num_blocks =
      d > 0 ? static_cast<int>((n + kBlock - 1) / kBlock) : 0;
  ParallelFor(0, num_blocks, num_threads, [&](int block, int) {
    const long begin = static_cast<long>(block) * kBlock;
    const int rows = static_cast<int>(std::min<long>(kBlock, n - begin));
    Sgemm(RowMajorView(embeddings.data() + begin * d, rows, d, d),
          RowMajorView(w.data(), d, 2 * h1, 2 * h1),
          0.f,
          projected_.data() + begin * 2 * h1,
          2 * h1);
  });
  for (int l = 1; l < model_.shape.NumGcnLayers(); ++l) {
    const auto weight = model_.params.GcnWeight(l);
    packed_gcn_weights_.emplace_back(RowMajorView(
        weight.data(), weight.rows(), weight.cols(), weight.cols()));
  }
  const auto fc1 = model_.params.Fc1Weight();
  packed_fc1_weight_ = PackedMatrix(
      RowMajorView(fc1.data(), fc1.rows(), fc1.cols(), fc1.cols()));
}

void GcnScorer::ScoreSubgraph(const QuerySubgraph& subgraph,
                              GcnWorkspace* ws,
                              std::vector<float>* logits) const {
  const GcnShape& shape = model_.shape;
  const GcnParameters<float>& params = model_.params;
  const int num_layers = shape.NumGcnLayers();
  const int n = subgraph.NumNodes();
  const int n1 = subgraph.num_one_hop;
  const AggregationMatrix g = ComputeAggregation(subgraph, model_.aggregation);

  // Layer 1: the embedding terms from the folded projections, then the
  // structural terms.
  const int h1 = shape.gcn_dims[0];
  const int rows1 = num_layers == 1 ? n1 : n;
  EnsureSize(&ws->a,
             static_cast<size_t>(n) * *std::max_element(shape.gcn_dims.begin(),
                                                        shape.gcn_dims.end()));
  float* h = ws->a.data();
  if (model_.DifferenceDim() > 0) {
    WriteEmbeddingTerms(subgraph, g, rows1, h);
  } else {
    const auto b1 = params.GcnBias(0);
    for (int i = 0; i < rows1; ++i) {
      std::copy(b1.data(), b1.data() + h1, h + static_cast<long>(i) * h1);
    }
  }
  if (structure_weight_.rows() > 0) AddStructureTerms(subgraph, g, rows1, h);
  Relu(static_cast<long>(rows1) * h1, h);

  // Layers 2..L.
  EnsureSize(&ws->b, ws->a.size());
  float* h_next = ws->b.data();
  for (int l = 1; l < num_layers; ++l) {
    const int in = shape.LayerInputDim(l);
    const int out = shape.gcn_dims[l];
    const int rows = (l == num_layers - 1) ? n1 : n;
    EnsureSize(&ws->cat, static_cast<size_t>(rows) * 2 * in);
    float* cat = ws->cat.data();
    for (int i = 0; i < rows; ++i) {
      float* crow = cat + static_cast<long>(i) * 2 * in;
      std::copy(h + static_cast<long>(i) * in,
                h + static_cast<long>(i + 1) * in,
                crow);
      float* agg = crow + in;
      std::fill(agg, agg + in, 0.f);
      for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
        Axpy(in, g.values[e], h + static_cast<long>(g.columns[e]) * in, agg);
      }
    }
    const auto bias = params.GcnBias(l);
    for (int i = 0; i < rows; ++i) {
      std::copy(
          bias.data(), bias.data() + out, h_next + static_cast<long>(i) * out);
    }
    Sgemm(RowMajorView(cat, rows, 2 * in, 2 * in),
          packed_gcn_weights_[l - 1],
          1.f,
          h_next,
          out);
    Relu(static_cast<long>(rows) * out, h_next);
    std::swap(h, h_next);
  }

  // FC layers on the 1-hop rows.
  const int dl = shape.gcn_dims.back();
  const int fc = shape.fc_dim;
  EnsureSize(&ws->cat, static_cast<size_t>(n1) * fc);
  float* u = ws->cat.data();
  const auto fc1_bias = params.Fc1Bias();
  for (int i = 0; i < n1; ++i) {
    std::copy(
        fc1_bias.data(), fc1_bias.data() + fc, u + static_cast<long>(i) * fc);
  }
  Sgemm(RowMajorView(h, n1, dl, dl), packed_fc1_weight_, 1.f, u, fc);
  const auto prelu = params.Prelu();
  const auto fc2 = params.Fc2Weight();
  logits->resize(n1);
  for (int i = 0; i < n1; ++i) {
    const float* urow = u + static_cast<long>(i) * fc;
    float z = params.Fc2Bias();
    for (int j = 0; j < fc; ++j) {
      const float v = urow[j] > 0 ? urow[j] : prelu(j) * urow[j];
      z += v * fc2(j);
    }
    (*logits)[i] = z;
  }
}

void GcnScorer::WriteEmbeddingTerms(const QuerySubgraph& subgraph,
                                    const AggregationMatrix& g,
                                    int rows,
                                    float* h) const {
  const int h1 = model_.shape.gcn_dims[0];
  const long pstride = 2 * h1;
  const std::vector<float> g1 = g.RowSums();
  // Features c (e_v - e_q): the projections are linear, so the factor c
  // scales the projected rows.
  const float c =
      QesFeatureFactor(subgraph, embeddings_, model_.feature_scaling);
  const float* pq = projected_.data() + subgraph.query * pstride;
  const auto b1 = model_.params.GcnBias(0);
  std::vector<float> base_a(h1), base_b(h1);
  for (int j = 0; j < h1; ++j) {
    base_a[j] = b1(j) - c * pq[j] - offset_(j);
    base_b[j] = c * pq[h1 + j] + offset_(h1 + j);
  }
  for (int i = 0; i < rows; ++i) {
    float* out = h + static_cast<long>(i) * h1;
    const float* pa = projected_.data() + subgraph.nodes[i] * pstride;
    const float gi = g1[i];
    // c = 1 without scaling: the products are exact, the scores unchanged.
    for (int j = 0; j < h1; ++j) {
      out[j] = c * pa[j] + base_a[j] - gi * base_b[j];
    }
    for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
      Axpy(h1,
           c * g.values[e],
           projected_.data() + subgraph.nodes[g.columns[e]] * pstride + h1,
           out);
    }
  }
}

void GcnScorer::AddStructureTerms(const QuerySubgraph& subgraph,
                                  const AggregationMatrix& g,
                                  int rows,
                                  float* h) const {
  const int extra = static_cast<int>(structure_weight_.rows());
  const int d = model_.DifferenceDim();
  const int h1 = model_.shape.gcn_dims[0];
  // Standardised structural features S; G S is formed row by row below.
  RowMatrix<float> x = QesStructureValues(
      subgraph, embeddings_, model_.feature_scaling, model_.structure_features);
  for (int j = 0; j < extra; ++j) {
    x.col(j) = (x.col(j).array() - model_.input_shift(d + j)) *
               model_.input_scale(d + j);
  }
  for (int i = 0; i < rows; ++i) {
    float* out = h + static_cast<long>(i) * h1;
    for (int j = 0; j < extra; ++j) {
      float aggregated = 0.f;
      for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
        aggregated += g.values[e] * x(g.columns[e], j);
      }
      Axpy(h1, x(i, j), structure_weight_.data() + j * 2 * h1, out);
      Axpy(h1, aggregated, structure_weight_.data() + j * 2 * h1 + h1, out);
    }
  }
}

std::vector<std::vector<float>> ScoreAllQueries(
    const GcnModel& model,
    const EmbeddingMatrix& embeddings,
    const KnnGraph& knn,
    const QesOptions& qes,
    int num_threads) {
  const GcnScorer scorer(model, embeddings, num_threads);
  const int n = knn.NumImages();
  const int threads = EffectiveNumThreads(num_threads);
  std::vector<std::unique_ptr<QesBuilder>> builders(threads);
  std::vector<GcnWorkspace> workspaces(threads);
  std::vector<QuerySubgraph> subgraphs(threads);
  std::vector<std::vector<float>> scores(n);
  ProgressLogger progress(n, "QES + GCN scoring", "queries");
  ParallelFor(0, n, threads, [&](int q, int t) {
    if (!builders[t]) {
      builders[t] =
          std::make_unique<QesBuilder>(knn, qes, model.structure_features);
    }
    builders[t]->Build(q, &subgraphs[t]);
    std::vector<float> logits;
    scorer.ScoreSubgraph(subgraphs[t], &workspaces[t], &logits);
    for (float& z : logits) z = Sigmoid(z);
    scores[q] = std::move(logits);
    progress.Increment();
  });
  return scores;
}

}  // namespace colmap_gcn
