// GCN inference cost.
//
// Default (quick): Google Benchmark cases on a 20,000-image synthetic
// collection, one thread: QES construction alone, QES + optimised GCN per
// query, and the straightforward reference forward pass, at k1 = 100,
// k2 = 5, u = 5, D = 256, paper-sized network (512-512-256-256, FC 256).
//
//   gcn_inference_benchmark [--benchmark_* flags]
//
// Full run: kNN + QES + GCN + pair selection (GcnPairGenerator) for every
// image of a synthetic collection, with peak memory:
//
//   gcn_inference_benchmark --full_run [--num_images 100000]
//                           [--num_threads 2]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include <sys/resource.h>

#include <benchmark/benchmark.h>

#include "gcn/gcn_inference.h"
#include "gcn_benchmark_data.h"
#include "math/sgemm.h"
#include "pairing/gcn_pair_generator.h"
#include "training/gcn_network.h"
#include "training/gcn_trainer.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

constexpr int kDim = 256;
constexpr int kQuickImages = 20000;
const QesOptions kQes{100, 5, 5};

struct Collection {
  EmbeddingMatrix embeddings;
  KnnGraph knn;
  GcnModel model;
};

// noise 0.05: tight clusters, QES of ~180 nodes; noise 1: nearly unclustered
// embeddings, QES close to the maximum k1 + k1 k2 = 600 nodes.
Collection* MakeCollection(float noise) {
  auto* c = new Collection;
  std::vector<int> clusters;
  c->embeddings = bench::SyntheticEmbeddings(
      kQuickImages, kDim, 1, &clusters, 5, 300, noise);
  c->knn = ComputeKnnForQes(c->embeddings, kQes, -1);
  c->model = InitializeGcnModel(GcnShape(), GcnAggregation::kSymmetric, 0);
  return c;
}

const Collection& DiffuseCollection() {
  static const Collection* collection = MakeCollection(1.f);
  return *collection;
}

const Collection& QuickCollection() {
  static const Collection* collection = MakeCollection(0.05f);
  return *collection;
}

void BM_QesBuild(benchmark::State& state) {
  const Collection& c = QuickCollection();
  QesBuilder builder(c.knn, kQes);
  QuerySubgraph subgraph;
  int q = 0;
  int64_t nodes = 0;
  for (auto _ : state) {
    builder.Build(q, &subgraph);
    nodes += subgraph.NumNodes();
    q = (q + 7919) % kQuickImages;
  }
  state.counters["nodes"] =
      benchmark::Counter(static_cast<double>(nodes) / state.iterations());
}
BENCHMARK(BM_QesBuild)->Unit(benchmark::kMicrosecond);

// What the pair generator does per query (the per-collection projection of
// layer 1 is done once, outside the loop; see the full run for its cost).
void BM_QesPlusGcnPerQuery(benchmark::State& state) {
  const Collection& c =
      state.range(0) == 0 ? QuickCollection() : DiffuseCollection();
  const GcnScorer scorer(c.model, c.embeddings, 1);
  QesBuilder builder(c.knn, kQes);
  QuerySubgraph subgraph;
  GcnWorkspace workspace;
  std::vector<float> logits;
  int q = 0;
  int64_t nodes = 0;
  for (auto _ : state) {
    builder.Build(q, &subgraph);
    scorer.ScoreSubgraph(subgraph, &workspace, &logits);
    benchmark::DoNotOptimize(logits.data());
    nodes += subgraph.NumNodes();
    q = (q + 7919) % kQuickImages;
  }
  state.counters["nodes"] =
      benchmark::Counter(static_cast<double>(nodes) / state.iterations());
  state.SetLabel(std::string("sgemm ") + SgemmKernelName());
}
BENCHMARK(BM_QesPlusGcnPerQuery)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("diffuse")
    ->Unit(benchmark::kMillisecond);

// The straightforward path (dense G, every layer on every node, Eigen).
void BM_ReferenceForwardPerQuery(benchmark::State& state) {
  const Collection& c =
      state.range(0) == 0 ? QuickCollection() : DiffuseCollection();
  QesBuilder builder(c.knn, kQes);
  QuerySubgraph subgraph;
  int q = 0;
  int64_t nodes = 0;
  for (auto _ : state) {
    builder.Build(q, &subgraph);
    nodes += subgraph.NumNodes();
    const GcnGraph<float> graph = MakeGcnGraph(c.model, subgraph, c.embeddings);
    benchmark::DoNotOptimize(GcnForwardReference(c.model.params, graph));
    q = (q + 7919) % kQuickImages;
  }
  state.counters["nodes"] =
      benchmark::Counter(static_cast<double>(nodes) / state.iterations());
}
BENCHMARK(BM_ReferenceForwardPerQuery)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("diffuse")
    ->Unit(benchmark::kMillisecond);

double ProcessCpuSeconds() {
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
         1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

long PeakRssMb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::atol(line.c_str() + 6) / 1024;
  }
  return -1;
}

int FullRun(int num_images, int num_threads) {
  std::printf(
      "full run: %d images, D = %d, k1 = %d, k2 = %d, u = %d, %d "
      "thread(s), sgemm %s\n",
      num_images,
      kDim,
      kQes.k1,
      kQes.k2,
      kQes.u,
      num_threads,
      SgemmKernelName().c_str());
  Timer timer;
  std::vector<int> clusters;
  const EmbeddingMatrix embeddings =
      bench::SyntheticEmbeddings(num_images, kDim, 2, &clusters);
  std::printf("  synthetic embeddings: %.1f s (%d clusters)\n",
              timer.ElapsedSeconds(),
              clusters.back() + 1);
  const GcnModel model =
      InitializeGcnModel(GcnShape(), GcnAggregation::kSymmetric, 0);
  std::vector<image_t> ids(num_images);
  for (int i = 0; i < num_images; ++i) ids[i] = i + 1;
  GcnPairingOptions options;
  options.k1 = kQes.k1;
  options.k2 = kQes.k2;
  options.u = kQes.u;
  options.num_threads = num_threads;
  timer.Restart();
  const double cpu_start = ProcessCpuSeconds();
  GcnPairGenerator generator(options, ids, embeddings, model);
  const double total = timer.ElapsedSeconds();
  const double cpu = ProcessCpuSeconds() - cpu_start;
  const GcnPairingStats& stats = generator.Stats();
  std::printf(
      "  kNN (exact, k = %d): %.1f s\n", kQes.RequiredK(), stats.knn_seconds);
  std::printf(
      "  QES + GCN, all queries: %.1f s (%.2f ms per query per "
      "thread)\n",
      stats.gcn_seconds,
      1e3 * stats.gcn_seconds * num_threads / num_images);
  std::printf(
      "  total pair generation: %.1f s (%.1f min); %d candidates, "
      "%zu pairs\n",
      total,
      total / 60,
      stats.num_candidates,
      generator.ScoredPairs().size());
  std::printf(
      "  process CPU time of pair generation: %.1f s (wall x threads "
      "= %.1f s; less means the machine was shared)\n",
      cpu,
      total * num_threads);
  std::printf("  peak RSS: %ld MB\n", PeakRssMb());
  return 0;
}

}  // namespace
}  // namespace colmap_gcn

int main(int argc, char** argv) {
  bool full_run = false;
  int num_images = 100000;
  int num_threads = 2;
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--full_run") == 0) {
      full_run = true;
    } else if (std::strcmp(argv[i], "--num_images") == 0 && i + 1 < argc) {
      num_images = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--num_threads") == 0 && i + 1 < argc) {
      num_threads = std::atoi(argv[++i]);
    } else {
      rest.push_back(argv[i]);
    }
  }
  if (full_run) return colmap_gcn::FullRun(num_images, num_threads);
  int rest_argc = static_cast<int>(rest.size());
  benchmark::Initialize(&rest_argc, rest.data());
  if (benchmark::ReportUnrecognizedArguments(rest_argc, rest.data())) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
