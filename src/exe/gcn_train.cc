#include "exe/gcn_train.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "training/gcn_training_run.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

// --GcnTraining.onnx_* (the CNN embedding, docs/retrieval.md) and where
// the scenes' images are.
void AddCnnTrainingOptions(OptionManager* manager,
                           CnnEmbeddingOptions* cnn,
                           SceneImageOptions* images) {
  manager->AddDefaultOption("GcnTraining.onnx_path",
                            &cnn->onnx_path,
                            "ONNX network for embedding onnx | vlad+onnx");
  manager->AddDefaultOption("GcnTraining.onnx_max_image_size",
                            &cnn->max_image_size,
                            "CNN input long side (px)");
  manager->AddDefaultOption("GcnTraining.onnx_size_multiple",
                            &cnn->size_multiple,
                            "CNN input sides are multiples of this");
  manager->AddDefaultOption(
      "GcnTraining.onnx_scale", &cnn->scale, "input = (pixel - mean) * scale");
  manager->AddDefaultOption("GcnTraining.onnx_mean", &cnn->mean);
  manager->AddDefaultOption(
      "GcnTraining.onnx_swap_rb", &cnn->swap_rb, "1: RGB input, 0: BGR");
  manager->AddDefaultOption(
      "GcnTraining.onnx_gem_p", &cnn->gem_p, "GeM pooling exponent");
  manager->AddDefaultOption("GcnTraining.onnx_center",
                            &cnn->center,
                            "subtract each collection's mean descriptor");
  manager->AddDefaultOption("GcnTraining.onnx_pca_dim",
                            &cnn->pca_dim,
                            "PCA-whitening dimension; 0: keep the network's");
  manager->AddDefaultOption("GcnTraining.onnx_pca_shrinkage",
                            &cnn->pca_shrinkage);
  manager->AddDefaultOption("GcnTraining.onnx_batch_size", &cnn->batch_size);
  manager->AddDefaultOption(
      "image_root",
      &images->image_root,
      "folder with <scene>/images for the CNN (the datasets gcn_benchmark "
      "read)");
  manager->AddDefaultOption(
      "GcnTraining.onnx_cache_dir",
      &images->cnn_cache_dir,
      "CNN descriptor caches; empty: beside each scene's base.db");
}

// --GcnTraining.*: labels, QES, network, optimiser, threshold and
// embedding. The list flags go to *gcn_dims and *lr_decay_epochs.
void AddGcnTrainingFlags(OptionManager* manager,
                         GcnTrainingPipelineOptions* options,
                         std::string* gcn_dims,
                         std::string* lr_decay_epochs) {
  GcnTrainingOptions* training = &options->training;
  manager->AddDefaultOption("GcnTraining.tau_mo", &options->labels.min_overlap);
  manager->AddDefaultOption("GcnTraining.tau_ct",
                            &options->labels.min_common_track_ratio);
  manager->AddDefaultOption("GcnTraining.k1", &training->qes.k1);
  manager->AddDefaultOption("GcnTraining.k2", &training->qes.k2);
  manager->AddDefaultOption("GcnTraining.u", &training->qes.u);
  manager->AddDefaultOption("GcnTraining.test_k1", &training->test_qes.k1);
  manager->AddDefaultOption("GcnTraining.test_k2", &training->test_qes.k2);
  manager->AddDefaultOption("GcnTraining.test_u", &training->test_qes.u);
  manager->AddEnumOption(
      "GcnTraining.optimizer", &training->optimizer, GcnOptimizerNames());
  manager->AddDefaultOption("GcnTraining.learning_rate",
                            &training->learning_rate);
  manager->AddDefaultOption("GcnTraining.num_epochs", &training->num_epochs);
  manager->AddDefaultOption("GcnTraining.batch_size", &training->batch_size);
  manager->AddDefaultOption("GcnTraining.gcn_dims",
                            gcn_dims,
                            "output sizes of the graph convolutions "
                            "(paper / gcn_clustering: 512,512,256,256)");
  manager->AddDefaultOption("GcnTraining.fc_dim", &training->shape.fc_dim);
  manager->AddEnumOption("GcnTraining.aggregation",
                         &training->aggregation,
                         GcnAggregationNames(),
                         "symmetric: the paper's L^-1/2 A L^-1/2; row: "
                         "gcn_clustering's neighbour mean");
  manager->AddEnumOption("GcnTraining.feature_scaling",
                         &training->feature_scaling,
                         QesFeatureScalingNames(),
                         "none: node features e_v - e_q; query: divided by "
                         "the query's RMS 1-hop distance (scale-free)");
  manager->AddEnumOption("GcnTraining.structure_features",
                         &training->structure_features,
                         QesStructureFeaturesNames(),
                         "none; reciprocal: append each node's kNN ranks "
                         "to and from the query and its neighbour overlaps "
                         "with the query; reciprocal_only: those and the "
                         "query-scaled distance, without e_v - e_q");
  manager->AddEnumOption("GcnTraining.initialization",
                         &training->initialization,
                         GcnInitializationNames(),
                         "docs/gcn.md");
  manager->AddDefaultOption("GcnTraining.lr_decay_epochs",
                            lr_decay_epochs,
                            "epochs (0-based) where the rate drops x0.1");
  manager->AddDefaultOption("GcnTraining.positive_weight",
                            &training->positive_weight,
                            "<= 0: balanced");
  manager->AddDefaultOption("GcnTraining.early_stopping_patience",
                            &training->early_stopping_patience);
  manager->AddDefaultOption("GcnTraining.threshold",
                            &options->threshold,
                            "stored in the model; < 0: the one maximising F "
                            "on the validation scenes");
  manager->AddDefaultOption("GcnTraining.seed", &training->seed);
  manager->AddDefaultOption("GcnTraining.num_threads", &training->num_threads);
  manager->AddEnumOption("GcnTraining.embedding",
                         &options->embedding,
                         ComputedEmbeddingTypeNames());
}

}  // namespace

int RunGcnTrain(int argc, char** argv) {
  GcnTrainingRunOptions run;
  std::string scenes;
  std::string validation_scenes;
  std::string test_scenes;
  GcnTrainingPipelineOptions& options = run.pipeline;
  GcnTrainingOptions& training = options.training;
  OptionManager manager(
      "gcn_train",
      "Trains the VLAD embedding and the GCN on labelled scenes prepared by "
      "`colmap gcn_benchmark` (<benchmark_path>/<scene>/base.db and "
      "labels/labels.csv) and writes a model file.");
  manager.AddRequiredOption("benchmark_path",
                            &run.benchmark_path,
                            "gcn_benchmark output folder with the scenes");
  manager.AddRequiredOption("output_path", &run.output_path, "model file");
  manager.AddDefaultOption(
      "scenes",
      &scenes,
      "training scenes (comma list; a+b: a collection of scenes a and b, "
      "pairs across them unrelated); empty: all others");
  manager.AddDefaultOption("validation_scenes",
                           &validation_scenes,
                           "for early stopping; empty: held-out queries");
  manager.AddDefaultOption(
      "test_scenes", &test_scenes, "held out entirely; GCN vs kNN is printed");
  std::string gcn_dims = "512,512,256,256";
  std::string lr_decay_epochs = "2,3";
  AddGcnTrainingFlags(&manager, &options, &gcn_dims, &lr_decay_epochs);
  AddCnnTrainingOptions(&manager, &options.cnn, &options.images);
  manager.AddDefaultOption("Vlad.num_words", &options.vlad.num_words);
  manager.AddDefaultOption("Vlad.dim", &options.vlad.dim);
  manager.AddDefaultOption("Vlad.seed", &options.vlad.seed);
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  options.vlad.num_threads = training.num_threads;
  options.cnn.num_threads = training.num_threads;
  training.shape.gcn_dims = ParseIntList(gcn_dims, "--GcnTraining.gcn_dims");
  training.lr_decay_epochs =
      ParseIntList(lr_decay_epochs, "--GcnTraining.lr_decay_epochs");
  manager.Check([&] {
    CHECK_OPTION(gcn_dims,
                 !training.shape.gcn_dims.empty() &&
                     std::all_of(training.shape.gcn_dims.begin(),
                                 training.shape.gcn_dims.end(),
                                 [](int dim) { return dim > 0; }),
                 "be a comma list of positive sizes");
    CHECK_OPTION(lr_decay_epochs,
                 std::all_of(training.lr_decay_epochs.begin(),
                             training.lr_decay_epochs.end(),
                             [](int epoch) { return epoch >= 0; }),
                 "be a comma list of epochs >= 0");
    // The number of threads first: the VLAD's copy is not a flag.
    CHECK_OPTION_NUM_THREADS(training.num_threads);
    options.Check();
  });

  run.scenes = SplitCommaList(scenes);
  run.validation_scenes = SplitCommaList(validation_scenes);
  run.test_scenes = SplitCommaList(test_scenes);

  const GcnTrainingRun result = RunGcnTraining(run);
  std::printf("wrote %s (%s) in %.1f s\n",
              run.output_path.c_str(),
              result.model.info.notes.c_str(),
              result.seconds);
  if (!result.test_comparisons.empty()) {
    std::printf("\nHeld-out scenes\n\n%s",
                FormatFixedKComparison(result.test_comparisons).c_str());
  }
  return 0;
}

}  // namespace colmap_gcn
