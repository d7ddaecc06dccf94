#pragma once

#include <string>
#include <vector>

#include "retrieval/cnn_embedding.h"
#include "retrieval/embedding.h"
#include "retrieval/knn.h"
#include "retrieval/vlad.h"
#include "scene/database.h"

namespace colmap_gcn {

// Where the per-image global descriptors come from (--GcnMatching.*).
struct GlobalDescriptorOptions {
  // Imported descriptors (.h5/.hdf5 as written by hloc, .npy with a names
  // list, or .txt); when set, they are used instead of VLAD.
  std::string descriptor_path = "";

  // A VLAD model trained by `colmap gcn_embedding_trainer`. Empty: train one
  // on the target database itself (cached as "<database>.gcn-vlad.bin").
  std::string embedding_path = "";

  // Training options for the self-trained model.
  VladOptions vlad;

  // The embedding when no descriptors are imported (built through its
  // EmbeddingSpec::build): vlad | onnx (a CNN on
  // the image files, centred, no PCA) | vlad+onnx (both, each half).
  EmbeddingType embedding = EmbeddingType::kVlad;

  // The CNN (embedding = onnx | vlad+onnx) and the folder of the images
  // (database names are relative to it), needed to run it.
  CnnEmbeddingOptions cnn;
  std::string image_path = "";

  // Keep "<database>.gcn-embedding.bin" (and the self-trained model) beside
  // the database, keyed on each image's features and the model checksum.
  bool use_cache = true;

  // Threads; -1 uses all cores. Results do not depend on it.
  int num_threads = -1;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// "<database_path>.gcn-vlad.bin".
std::string SelfTrainedModelPath(const std::string& database_path);

// The VLAD model trained on the database itself (or its cached copy, when
// the cache key — all images' feature keys and the training options — is
// unchanged).
VladEmbedding LoadOrTrainSelfEmbedding(const Database& database,
                                       const VladOptions& options,
                                       bool use_cache);

// One L2-normalised row per database image, ascending image id (returned in
// *image_ids).
EmbeddingMatrix ComputeGlobalDescriptors(const Database& database,
                                         const GlobalDescriptorOptions& options,
                                         std::vector<image_t>* image_ids);

}  // namespace colmap_gcn
