#pragma once

#include <string>
#include <vector>

#include "evaluation/labels.h"
#include "gcn/gcn_model.h"
#include "math/precision_recall.h"
#include "retrieval/cnn_embedding.h"
#include "retrieval/model_embedding.h"
#include "retrieval/vlad.h"
#include "training/gcn_trainer.h"
#include "training/pair_set_scoring.h"

namespace colmap_gcn {

// A scene prepared for training: its COLMAP database (features extracted)
// and its ground-truth pair labels. `colmap gcn_benchmark` prepares both
// (<output>/<scene>/base.db and <output>/<scene>/labels/labels.csv).
//
// Or a collection of such scenes, named "a+b+c": all of their images, the
// pairs across scenes labelled as sharing nothing. Unrelated photos, as in
// an internet collection, are the negatives small real scenes lack.
struct LabelledScene {
  std::string name;
  std::string database_path;
  std::string labels_path;
  std::vector<LabelledScene> parts;  // a collection's scenes, else empty
};

// The scenes of a gcn_benchmark output folder; `names` selects some (all
// with both files when empty; "a+b" a collection of scenes a and b).
// Throws Error naming a missing scene.
std::vector<LabelledScene> FindLabelledScenes(
    const std::string& benchmark_path, const std::vector<std::string>& names);

// `scenes` without any that shares a scene with `held_out` (names; "a+b"
// holds out a and b, and a collection containing a held-out scene goes).
std::vector<LabelledScene> WithoutHeldOutScenes(
    const std::vector<LabelledScene>& scenes,
    const std::vector<std::string>& held_out);

// Where a labelled scene's image files and CNN descriptor cache are (CNN
// embeddings read the images; the corpus's databases name them relative
// to <image_root>/<scene>/images, as gcn_benchmark extracted them).
struct SceneImageOptions {
  std::string image_root = "../shared/datasets";

  // CNN caches as <cnn_cache_dir>/<scene>.gcn-cnn-embedding.bin; empty:
  // beside each scene's database.
  std::string cnn_cache_dir = "";

  std::string ImagePath(const LabelledScene& scene) const;
  std::string CnnCachePath(const LabelledScene& scene) const;
};

struct GcnTrainingPipelineOptions {
  // The model's embedding: vlad | onnx | vlad+onnx (each part L2-normalised
  // and scaled by 1/sqrt(2)).
  EmbeddingType embedding = EmbeddingType::kVlad;

  // The shared VLAD: one codebook + whitening trained on all training
  // databases, stored in the model so inference embeds alike.
  VladOptions vlad;

  // The CNN (onnx_path, preprocessing, pooling, PCA-whitening learned on the
  // training databases), stored in the model with the network's checksum.
  CnnEmbeddingOptions cnn;
  SceneImageOptions images;

  // Labels: matchable when overlap >= tau_MO or common tracks >= tau_CT.
  PairLabelOptions labels;

  // The network and optimiser (GcnTrainer).
  GcnTrainingOptions training;

  // Decision threshold stored in the model. < 0: the one maximising the
  // mean pair-set F over the validation scenes (SelectGcnThreshold), so
  // the class-balanced loss's uncalibrated scores become a useful operating
  // point, and training.threshold only serves the epoch statistics; a fixed
  // threshold (> 0) replaces training.threshold too.
  double threshold = 0.5;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// The collection of `parts`: their embeddings stacked in order, their
// pairs re-indexed, every pair across parts unrelated.
GcnTrainingScene MergeTrainingScenes(
    const std::string& name, const std::vector<GcnTrainingScene>& parts);

// Embeds every scene with `vlad` and turns its labels into row-index pairs.
GcnTrainingScene MakeTrainingScene(const LabelledScene& scene,
                                   const VladEmbedding& vlad,
                                   const PairLabelOptions& label_options,
                                   int num_threads);

// The same with any model embedding: each database embedded by
// embedder.EmbedDatabase (images and cache as `images` says), then the
// whole scene or collection by embedder.Finalize (CNN centring and PCA).
GcnTrainingScene MakeTrainingScene(const LabelledScene& scene,
                                   const ModelEmbedder& embedder,
                                   const SceneImageOptions& images,
                                   const PairLabelOptions& label_options);

// Trains the embedding on the training scenes, then the GCN (validating on
// validation_scenes, or on a held-out fraction of queries when empty), and
// returns the model with the embedding, thresholds and notes filled in.
GcnModel TrainGcnModel(const std::vector<LabelledScene>& training_scenes,
                       const std::vector<LabelledScene>& validation_scenes,
                       const GcnTrainingPipelineOptions& options);

}  // namespace colmap_gcn
