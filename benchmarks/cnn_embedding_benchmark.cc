// CNN embedding speed and ranking quality on labelled scenes:
//
//   cnn_embedding_benchmark <network.onnx> <max_image_size> <num_threads>
//       <benchmark_dir> <image_root> <scene>...
//
// For each scene (<benchmark_dir>/<scene>/base.db + labels/labels.csv, the
// images in <image_root>/<scene>/images): CNN descriptors without a cache
// (wall time per image), the average precision of ranking all of the
// scene's pairs by similarity against its labels (tau_CT 0.15), for the CNN
// (GeM, centred) and the self-trained VLAD; then the pooled "same scene" AP
// over all scenes together (a pair is positive when both images come from
// the same scene; the CNN centred over the pool).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "retrieval/cnn_embedding.h"
#include "retrieval/global_descriptors.h"
#include "retrieval/model_embedding.h"
#include "training/gcn_trainer.h"
#include "training/gcn_training.h"
#include "util/error.h"
#include "util/file.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

double AllPairsAp(const EmbeddingMatrix& embeddings,
                  const GcnTrainingScene& scene) {
  const int n = static_cast<int>(embeddings.rows());
  std::vector<std::vector<char>> positive(n, std::vector<char>(n, 0));
  for (const auto& [i, j] : scene.positive_pairs) {
    positive[i][j] = positive[j][i] = 1;
  }
  std::vector<float> scores;
  std::vector<uint8_t> labels;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      scores.push_back(embeddings.row(i).dot(embeddings.row(j)));
      labels.push_back(positive[i][j]);
    }
  }
  return AveragePrecision(scores, labels);
}

int Run(int argc, char** argv) {
  if (argc < 7) {
    std::fprintf(stderr,
                 "usage: %s <network.onnx> <max_image_size> <num_threads> "
                 "<benchmark_dir> <image_root> <scene>...\n",
                 argv[0]);
    return 2;
  }
  CnnEmbeddingOptions options;
  options.onnx_path = argv[1];
  options.max_image_size = std::atoi(argv[2]);
  options.num_threads = std::atoi(argv[3]);
  options.progress_every = 0;
  const std::string benchmark_dir = argv[4];
  SceneImageOptions images;
  images.image_root = argv[5];
  std::vector<std::string> names(argv + 6, argv + argc);

  const CnnNetwork network(options);
  const CnnEmbeddingModel model = MakeCnnEmbeddingModel(network);
  std::printf(
      "network %s, %d-D, input long side %d, %d thread(s)\n\n"
      "| scene | images | pairs | matchable | ms/image | AP CNN | AP VLAD |\n"
      "|---|---:|---:|---:|---:|---:|---:|\n",
      options.onnx_path.c_str(),
      network.DescriptorDim(),
      options.max_image_size,
      options.num_threads);
  std::vector<FloatMatrix> raws;
  double total_seconds = 0;
  size_t total_images = 0;
  double sum_cnn_ap = 0, sum_vlad_ap = 0;
  for (const LabelledScene& scene : FindLabelledScenes(benchmark_dir, names)) {
    const Database database(scene.database_path);
    std::vector<image_t> ids;
    const Timer timer;
    const FloatMatrix raw = ComputeDatabaseCnnDescriptors(
        database, network, images.ImagePath(scene), "", &ids);
    const double seconds = timer.ElapsedSeconds();
    total_seconds += seconds;
    total_images += ids.size();
    raws.push_back(raw);
    VladOptions vlad_options;
    vlad_options.num_threads = options.num_threads;
    const VladEmbedding vlad =
        LoadOrTrainSelfEmbedding(database, vlad_options, /*use_cache=*/false);
    const GcnTrainingScene labelled =
        MakeTrainingScene(scene, vlad, PairLabelOptions(), 1);
    const double cnn_ap = AllPairsAp(model.Apply(raw), labelled);
    const double vlad_ap = AllPairsAp(labelled.embeddings, labelled);
    sum_cnn_ap += cnn_ap;
    sum_vlad_ap += vlad_ap;
    const size_t n = ids.size();
    std::printf("| %s | %zu | %zu | %zu | %.1f | %.3f | %.3f |\n",
                scene.name.c_str(),
                n,
                n * (n - 1) / 2,
                labelled.positive_pairs.size(),
                1000 * seconds / n,
                cnn_ap,
                vlad_ap);
  }
  std::printf("| mean | %zu | | | %.1f | %.3f | %.3f |\n",
              total_images,
              1000 * total_seconds / total_images,
              sum_cnn_ap / raws.size(),
              sum_vlad_ap / raws.size());
  // Pooled: every pair across scenes negative, within a scene positive.
  Eigen::Index rows = 0;
  for (const auto& raw : raws) rows += raw.rows();
  FloatMatrix pooled(rows, network.DescriptorDim());
  std::vector<int> scene_of;
  rows = 0;
  for (size_t s = 0; s < raws.size(); ++s) {
    pooled.middleRows(rows, raws[s].rows()) = raws[s];
    rows += raws[s].rows();
    scene_of.insert(scene_of.end(), raws[s].rows(), static_cast<int>(s));
  }
  for (const bool center : {false, true}) {
    CnnEmbeddingModel pooled_model = model;
    pooled_model.options.center = center;
    const EmbeddingMatrix embeddings = pooled_model.Apply(pooled);
    std::vector<float> scores;
    std::vector<uint8_t> labels;
    for (Eigen::Index i = 0; i < embeddings.rows(); ++i) {
      for (Eigen::Index j = i + 1; j < embeddings.rows(); ++j) {
        scores.push_back(embeddings.row(i).dot(embeddings.row(j)));
        labels.push_back(scene_of[i] == scene_of[j]);
      }
    }
    std::printf("\nsame-scene AP, %zu scenes pooled (%lld images)%s: %.3f",
                raws.size(),
                static_cast<long long>(embeddings.rows()),
                center ? ", centred" : "",
                AveragePrecision(scores, labels));
  }
  std::printf(
      "\ntotal CNN time %.1f s for %zu images\n", total_seconds, total_images);
  return 0;
}

}  // namespace
}  // namespace colmap_gcn

int main(int argc, char** argv) {
  try {
    return colmap_gcn::Run(argc, argv);
  } catch (const colmap_gcn::Error& error) {
    std::fprintf(stderr, "ERROR: %s\n", error.what());
    return 1;
  }
}
