#pragma once

#include <ostream>
#include <string>

#include "retrieval/cnn_embedding.h"
#include "util/option_check.h"

namespace colmap_gcn {

class OptionManager;

// Every embedding, listed once: its EmbeddingType value, its name (for
// --GcnMatching.embedding and the type a model file stores) and the function,
// defined in the embedding's own file, that returns its EmbeddingSpec
// (embedding_spec.h). Like COLMAP's CAMERA_MODEL_CASES, the enum, the names
// and the table GetEmbeddingSpec reads expand from this list, so adding an
// embedding is one line here. The order is the order of the names in -h.
#define COLMAP_GCN_EMBEDDINGS(EMBEDDING)                   \
  EMBEDDING(kVlad, "vlad", VladEmbeddingSpec)              \
  EMBEDDING(kOnnx, "onnx", OnnxEmbeddingSpec)              \
  EMBEDDING(kVladOnnx, "vlad+onnx", VladOnnxEmbeddingSpec) \
  EMBEDDING(kImported, "imported", ImportedEmbeddingSpec)  \
  /* the end of the list: a new embedding adds one line above */

// The global embedding of an image: what the kNN graph, the GCN and the
// adaptive generators compare images by. kDefault is no embedding but the
// choice left to the generator: the GCN model's, or for knn VLAD (or the
// imported descriptors when a descriptor file is named).
enum class EmbeddingType {
  kDefault,
#define COLMAP_GCN_EMBEDDING_VALUE(value, name, spec) value,
  COLMAP_GCN_EMBEDDINGS(COLMAP_GCN_EMBEDDING_VALUE)
#undef COLMAP_GCN_EMBEDDING_VALUE
};

// default | vlad | onnx | vlad+onnx | imported: --GcnMatching.embedding.
const EnumNames<EmbeddingType>& EmbeddingTypeNames();
// vlad | onnx | vlad+onnx: the embeddings computed from a database (and
// trained by gcn_train).
const EnumNames<EmbeddingType>& ComputedEmbeddingTypeNames();

// Its name in EmbeddingTypeNames(), for messages.
std::ostream& operator<<(std::ostream& stream, EmbeddingType type);

bool EmbeddingUsesVlad(EmbeddingType type);
bool EmbeddingUsesCnn(EmbeddingType type);

// Where the embeddings come from: the embedding as stored in a GCN model
// file. Opaque to the GCN: `blob` holds the VLAD codebook / whitening, the
// CNN's PCA and network checksum, or both (EmbeddingConfigType).
struct GcnEmbeddingConfig {
  std::string type;  // e.g. "vlad" or "imported:<name>"
  int dim = 0;       // descriptor dimension D (== GcnShape::input_dim)
  std::string blob;
};

// The EmbeddingType of a model's config: the embedding named config.type, or
// "<name>:<detail>" (e.g. "imported:<name>" is kImported); throws Error for an
// unknown type.
EmbeddingType EmbeddingConfigType(const GcnEmbeddingConfig& config);

// The embedding flags gcn_matcher's gcn and knn generators share
// (--GcnMatching.embedding, descriptor_path, onnx_path, image_path, onnx_*,
// onnx_batch_size), parsed once into this struct.
struct EmbeddingOptions {
  // The embedding asked for. gcn: default takes the model's, others must be
  // the model's; knn: default is vlad, or the imported descriptors when
  // descriptor_path is set.
  EmbeddingType type = EmbeddingType::kDefault;

  // Imported global descriptors (.h5 / .npy / .txt).
  std::string descriptor_path = "";

  // The ONNX network (embedding onnx / vlad+onnx) and the folder of the
  // images it runs on (the one given to feature_extractor; database names
  // are relative to it).
  std::string onnx_path = "";
  std::string image_path = "";

  // The CNN preprocessing the user set (-1: the model's, or MobileNetV2's
  // for knn; set values must match a model's) and images per forward pass.
  CnnEmbeddingOverrides onnx;
  int onnx_batch_size = 1;

  // Throws OptionError naming the first invalid field (a CNN type without
  // onnx_path or image_path, imported without descriptor_path).
  void Check() const;
};

// Binds --GcnMatching.embedding, descriptor_path, onnx_path, image_path,
// onnx_* and onnx_batch_size to *options (several generators may bind them:
// a given flag sets all).
void AddEmbeddingOptions(OptionManager* manager, EmbeddingOptions* options);

}  // namespace colmap_gcn
