// GCN training throughput on synthetic clustered embeddings (same cluster =
// matchable), paper-sized network, D = 256, training QES k1 = 100, k2 = 5,
// u = 10, SGD batch 16. Trains one epoch over --subgraphs samples and reports
// the time per subgraph.
//
//   gcn_training_benchmark [--subgraphs 400] [--num_threads 2]
//   gcn_training_benchmark --subgraphs 10000     (the 10,000-subgraph target)
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "gcn_benchmark_data.h"
#include "math/sgemm.h"
#include "training/gcn_trainer.h"
#include "util/timer.h"

int main(int argc, char** argv) {
  using namespace colmap_gcn;
  int subgraphs = 400;
  int num_threads = 2;
  int images_per_scene = 1000;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--subgraphs") == 0) {
      subgraphs = std::atoi(argv[i + 1]);
    } else if (std::strcmp(argv[i], "--num_threads") == 0) {
      num_threads = std::atoi(argv[i + 1]);
    } else if (std::strcmp(argv[i], "--images_per_scene") == 0) {
      images_per_scene = std::atoi(argv[i + 1]);
    } else {
      std::fprintf(stderr, "unknown argument %s\n", argv[i]);
      return 1;
    }
  }
  const int num_scenes =
      std::max(1, (subgraphs + images_per_scene - 1) / images_per_scene);
  std::vector<GcnTrainingScene> scenes(num_scenes);
  int64_t positives = 0;
  for (int s = 0; s < num_scenes; ++s) {
    std::vector<int> cluster;
    scenes[s].name = "synthetic" + std::to_string(s);
    scenes[s].embeddings = bench::SyntheticEmbeddings(
        images_per_scene, 256, 100 + s, &cluster, 5, 200, 0.08f);
    for (int i = 0; i < images_per_scene; ++i) {
      for (int j = i + 1; j < images_per_scene && cluster[j] == cluster[i];
           ++j) {
        scenes[s].positive_pairs.emplace_back(i, j);
      }
    }
    positives += scenes[s].positive_pairs.size();
  }
  GcnTrainingOptions options;
  options.num_epochs = 1;
  options.validation_fraction = 0;
  options.max_samples_per_epoch = subgraphs;
  options.num_threads = num_threads;
  std::printf(
      "training benchmark: %d scene(s) x %d images, %lld positive "
      "pairs, %d subgraphs, QES k1 %d k2 %d u %d, batch %d, %d "
      "thread(s), sgemm %s\n",
      num_scenes,
      images_per_scene,
      static_cast<long long>(positives),
      subgraphs,
      options.qes.k1,
      options.qes.k2,
      options.qes.u,
      options.batch_size,
      num_threads,
      SgemmKernelName().c_str());
  Timer timer;
  GcnTrainer trainer(options);
  trainer.Train(scenes);
  const double total = timer.ElapsedSeconds();
  const double epoch = trainer.History().back().seconds;
  std::printf(
      "one epoch over %d subgraphs: %.1f s (%.1f ms per subgraph); "
      "total incl. kNN and set-up %.1f s; 10,000 subgraphs ~ %.1f "
      "min\n",
      subgraphs,
      epoch,
      1e3 * epoch / subgraphs,
      total,
      epoch / subgraphs * 10000 / 60);
  return 0;
}
