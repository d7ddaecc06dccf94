// C++ vs the independent PyTorch implementation in
// scripts/research/gcn_reference.py: logits and loss gradients w.r.t. every
// parameter. Skipped when no Python with torch is available.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "gcn/gcn_inference.h"
#include "gcn/gcn_test_utils.h"
#include "test_utils.h"
#include "training/gcn_network.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

// Runs the reference script on the case directories with the first Python
// that has torch (COLMAP_GCN_PYTHON, /usr/bin/python3, python3). Returns false
// if none has it (the script exits 77 when the import fails).
bool RunTorchReference(const std::string& args, std::string* output) {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("COLMAP_GCN_PYTHON")) {
    candidates.push_back(env);
  }
  candidates.push_back("/usr/bin/python3");
  candidates.push_back("python3");
  const std::string script =
      std::string(COLMAP_GCN_SOURCE_DIR) + "/scripts/research/gcn_reference.py";
  for (const std::string& python : candidates) {
    const int code =
        test::RunShell(python + " " + script + " check " + args, output);
    if (code == 77 || code == 127) continue;  // no torch / no interpreter
    EXPECT_EQ(code, 0) << *output;
    return true;
  }
  return false;
}

template <typename T>
void WriteRaw(const std::string& path, const T* data, size_t count) {
  std::ofstream file(path, std::ios::binary);
  file.write(reinterpret_cast<const char*>(data), sizeof(T) * count);
  EXPECT_TRUE(file.good()) << path;
}

std::vector<double> ReadDoubles(const std::string& path) {
  const std::string bytes = ReadTextFile(path);
  std::vector<double> values(bytes.size() / sizeof(double));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(double));
  return values;
}

struct TorchCase {
  GcnShape shape;
  GcnAggregation aggregation;
  QesOptions qes;
  std::vector<int> queries;
};

struct CaseResult {
  std::string dir;
  GcnShape shape;
  GcnParameters<float> gradient;
  float loss = 0;
  std::vector<ColVector<float>> reference_logits;
  std::vector<std::vector<float>> optimised_logits;
};

// Writes the inputs of one case to `d` and computes the C++ side.
CaseResult PrepareCase(const TorchCase& c, const std::string& d) {
  std::vector<int> clusters;
  const EmbeddingMatrix embeddings = test::ClusteredEmbeddings(
      {15, 9, 22, 14}, c.shape.input_dim, 0.3f, 7, &clusters);
  const KnnGraph knn = test::BruteForceKnn(embeddings, c.qes.RequiredK());
  GcnModel model = InitializeGcnModel(c.shape, c.aggregation, 3);
  // Non-trivial standardisation, biases and PReLU slopes.
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> uniform(-0.1f, 0.1f);
  for (int i = 0; i < c.shape.input_dim; ++i) {
    model.input_shift(i) = 0.05f * uniform(rng);
    model.input_scale(i) = 3.f + 10.f * uniform(rng);
  }
  for (int l = 0; l < c.shape.NumGcnLayers(); ++l) {
    for (int j = 0; j < c.shape.gcn_dims[l]; ++j) {
      model.params.GcnBias(l)(j) = uniform(rng);
    }
  }
  for (int j = 0; j < c.shape.fc_dim; ++j) {
    model.params.Fc1Bias()(j) = uniform(rng);
    model.params.Prelu()(j) = 0.25f + uniform(rng);
  }
  model.params.Fc2Bias() = 0.05f;
  const float positive_weight = 1.7f;

  CreateDirIfNotExists(d);
  std::ofstream meta(JoinPaths(d, "meta.txt"));
  meta << "input_dim " << c.shape.input_dim << "\ngcn_dims";
  for (int dim : c.shape.gcn_dims) meta << " " << dim;
  meta << "\nfc_dim " << c.shape.fc_dim << "\naggregation "
       << GcnAggregationName(c.aggregation) << "\npositive_weight "
       << positive_weight << "\nnum_graphs " << c.queries.size() << "\n";
  WriteRaw(JoinPaths(d, "weights.bin"),
           model.params.Values().data(),
           model.params.Size());
  std::vector<float> norm(model.input_shift.data(),
                          model.input_shift.data() + c.shape.input_dim);
  norm.insert(norm.end(),
              model.input_scale.data(),
              model.input_scale.data() + c.shape.input_dim);
  WriteRaw(JoinPaths(d, "norm.bin"), norm.data(), norm.size());

  CaseResult result;
  result.dir = d;
  result.shape = c.shape;
  result.gradient = GcnParameters<float>(c.shape);
  GcnParameters<float>& gradient = result.gradient;
  float& loss = result.loss;
  std::vector<ColVector<float>>& reference_logits = result.reference_logits;
  std::vector<std::vector<float>>& optimised_logits = result.optimised_logits;
  GcnScorer scorer(model, embeddings, 1);
  GcnWorkspace workspace;
  for (size_t g = 0; g < c.queries.size(); ++g) {
    const QuerySubgraph s = BuildQuerySubgraph(knn, c.queries[g], c.qes);
    GcnGraph<float> graph = MakeGcnGraph(model, s, embeddings);
    graph.labels.resize(s.num_one_hop);
    for (int i = 0; i < s.num_one_hop; ++i) {
      graph.labels[i] = clusters[s.nodes[i]] == clusters[s.query];
    }
    loss += GcnLossAndGradient<float>(
        model.params, graph, positive_weight, &gradient, nullptr);
    reference_logits.push_back(GcnForwardReference(model.params, graph));
    optimised_logits.emplace_back();
    scorer.ScoreSubgraph(s, &workspace, &optimised_logits.back());

    meta << "graph" << g << " " << s.NumNodes() << " " << s.num_one_hop << "\n";
    const auto raw = QesFeatures(s, embeddings);
    WriteRaw(JoinPaths(d, "features_" + std::to_string(g) + ".bin"),
             raw.data(),
             raw.size());
    const Eigen::MatrixXf adjacency = test::DenseAdjacency(s);
    WriteRaw(JoinPaths(d, "adjacency_" + std::to_string(g) + ".bin"),
             adjacency.data(),
             adjacency.size());  // symmetric: order-free
    std::vector<float> labels(graph.labels.begin(), graph.labels.end());
    WriteRaw(JoinPaths(d, "labels_" + std::to_string(g) + ".bin"),
             labels.data(),
             labels.size());
  }
  meta.close();
  return result;
}

void CompareCase(const CaseResult& r) {
  const std::string& d = r.dir;
  const GcnParameters<float>& gradient = r.gradient;
  const auto& reference_logits = r.reference_logits;
  const auto& optimised_logits = r.optimised_logits;
  for (size_t g = 0; g < reference_logits.size(); ++g) {
    const std::vector<double> torch_logits =
        ReadDoubles(JoinPaths(d, "out_logits_" + std::to_string(g) + ".bin"));
    ASSERT_EQ(torch_logits.size(),
              static_cast<size_t>(reference_logits[g].size()));
    for (size_t i = 0; i < torch_logits.size(); ++i) {
      const double tol = 1e-4 * std::max(1.0, std::abs(torch_logits[i]));
      EXPECT_NEAR(reference_logits[g](i), torch_logits[i], tol)
          << g << " " << i;
      EXPECT_NEAR(optimised_logits[g][i], torch_logits[i], tol)
          << g << " " << i;
    }
  }
  const double torch_loss = ReadDoubles(JoinPaths(d, "out_loss.bin"))[0];
  EXPECT_NEAR(r.loss, torch_loss, 1e-4 * std::max(1.0, std::abs(torch_loss)));

  const std::vector<double> torch_grads =
      ReadDoubles(JoinPaths(d, "out_grads.bin"));
  ASSERT_EQ(torch_grads.size(), gradient.Size());
  // Per parameter group: |c++ - torch| <= 1e-4 * max(1, max |torch| in group).
  const GcnParameterLayout& layout = gradient.Layout();
  std::vector<std::pair<std::string, std::pair<size_t, size_t>>> groups;
  for (int l = 0; l < r.shape.NumGcnLayers(); ++l) {
    groups.push_back(
        {"W" + std::to_string(l), {layout.gcn_weight[l], layout.gcn_bias[l]}});
    groups.push_back(
        {"b" + std::to_string(l),
         {layout.gcn_bias[l], layout.gcn_bias[l] + r.shape.gcn_dims[l]}});
  }
  groups.push_back({"fc1_weight", {layout.fc1_weight, layout.fc1_bias}});
  groups.push_back({"fc1_bias", {layout.fc1_bias, layout.prelu}});
  groups.push_back({"prelu", {layout.prelu, layout.fc2_weight}});
  groups.push_back({"fc2_weight", {layout.fc2_weight, layout.fc2_bias}});
  groups.push_back({"fc2_bias", {layout.fc2_bias, layout.size}});
  for (const auto& [name, range] : groups) {
    double scale = 0;
    for (size_t i = range.first; i < range.second; ++i) {
      scale = std::max(scale, std::abs(torch_grads[i]));
    }
    EXPECT_GT(scale, 0.0) << name << ": all-zero gradient";
    const double tol = 1e-4 * std::max(1.0, scale);
    int failures = 0;
    for (size_t i = range.first; i < range.second && failures < 5; ++i) {
      if (std::abs(gradient.Values()[i] - torch_grads[i]) > tol) {
        ++failures;
        ADD_FAILURE() << name << " [" << i - range.first << "]: C++ "
                      << gradient.Values()[i] << " torch " << torch_grads[i];
      }
    }
  }
}

TEST(GcnTorchReference, OutputsAndGradientsAgree) {
  const std::vector<TorchCase> cases = {
      {test::SmallShape(16),
       GcnAggregation::kSymmetric,
       {10, 4, 5},
       {0, 17, 40}},
      {test::SmallShape(16),
       GcnAggregation::kRowNormalized,
       {10, 4, 5},
       {3, 25}},
      {GcnShape(), GcnAggregation::kSymmetric, {20, 5, 5}, {8, 50}},
  };
  TemporaryDirectory dir("gcn_torch_test");
  std::vector<CaseResult> results;
  std::string dirs;
  for (size_t i = 0; i < cases.size(); ++i) {
    results.push_back(
        PrepareCase(cases[i], JoinPaths(dir.Path(), std::to_string(i))));
    dirs += " " + results.back().dir;
  }
  std::string output;
  if (!RunTorchReference(dirs, &output)) {
    GTEST_SKIP() << "no python3 with torch and numpy";
  }
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    CompareCase(results[i]);
  }
}

}  // namespace
}  // namespace colmap_gcn
