#include "retrieval/embedding.h"

#include "retrieval/embedding_spec.h"
#include "util/error.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {

const EnumNames<EmbeddingType>& EmbeddingTypeNames() {
  static const EnumNames<EmbeddingType> names = {
      {"default", EmbeddingType::kDefault},
#define COLMAP_GCN_EMBEDDING_NAME(value, name, spec) \
  {name, EmbeddingType::value},
      COLMAP_GCN_EMBEDDINGS(COLMAP_GCN_EMBEDDING_NAME)
#undef COLMAP_GCN_EMBEDDING_NAME
  };
  return names;
}

const EmbeddingSpec& GetEmbeddingSpec(const EmbeddingType type) {
  static const std::vector<std::pair<EmbeddingType, EmbeddingSpec>> specs = {
#define COLMAP_GCN_EMBEDDING_ENTRY(value, name, spec) \
  {EmbeddingType::value, spec()},
      COLMAP_GCN_EMBEDDINGS(COLMAP_GCN_EMBEDDING_ENTRY)
#undef COLMAP_GCN_EMBEDDING_ENTRY
  };
  for (const auto& [entry, spec] : specs) {
    if (entry == type) return spec;
  }
  ThrowError("no embedding is registered as \"", type, "\"");
}

const EnumNames<EmbeddingType>& ComputedEmbeddingTypeNames() {
  static const EnumNames<EmbeddingType> names = {
      {"vlad", EmbeddingType::kVlad},
      {"onnx", EmbeddingType::kOnnx},
      {"vlad+onnx", EmbeddingType::kVladOnnx}};
  return names;
}

std::ostream& operator<<(std::ostream& stream, const EmbeddingType type) {
  return stream << EnumName(EmbeddingTypeNames(), type);
}

bool EmbeddingUsesVlad(const EmbeddingType type) {
  return type == EmbeddingType::kVlad || type == EmbeddingType::kVladOnnx;
}

bool EmbeddingUsesCnn(const EmbeddingType type) {
  return type == EmbeddingType::kOnnx || type == EmbeddingType::kVladOnnx;
}

EmbeddingType EmbeddingConfigType(const GcnEmbeddingConfig& config) {
  for (const auto& [name, type] : EmbeddingTypeNames()) {
    if (type != EmbeddingType::kDefault &&
        (config.type == name || StringStartsWith(config.type, name + ":"))) {
      return type;
    }
  }
  ThrowError(
      "the GCN model has an unknown embedding type \"", config.type, "\"");
}

void EmbeddingOptions::Check() const {
  onnx.Check();
  CHECK_OPTION_GE(onnx_batch_size, 1);
  const std::string name = EnumName(EmbeddingTypeNames(), type);
  if (EmbeddingUsesCnn(type)) {
    CHECK_OPTION(
        onnx_path,
        !onnx_path.empty(),
        "name the ONNX network when --GcnMatching.embedding is " + name);
    CHECK_OPTION(image_path,
                 !image_path.empty(),
                 "name the image folder (the one given to feature_extractor) "
                 "when --GcnMatching.embedding is " +
                     name);
  }
  if (type == EmbeddingType::kImported) {
    CHECK_OPTION(descriptor_path,
                 !descriptor_path.empty(),
                 "name the descriptor file when --GcnMatching.embedding is "
                 "imported");
  }
}

void AddEmbeddingOptions(OptionManager* manager, EmbeddingOptions* options) {
  manager->AddDefaultOption("GcnMatching.descriptor_path",
                            &options->descriptor_path,
                            "imported global descriptors (.h5 | .npy | .txt)");
  manager->AddEnumOption("GcnMatching.embedding",
                         &options->type,
                         EmbeddingTypeNames(),
                         "default: the model's (gcn), vlad (knn)");
  manager->AddDefaultOption("GcnMatching.onnx_path",
                            &options->onnx_path,
                            "ONNX network for embedding=onnx (OpenCV DNN)");
  manager->AddDefaultOption(
      "GcnMatching.image_path",
      &options->image_path,
      "folder of the images (as given to feature_extractor); needed by onnx");
  AddCnnEmbeddingOverrideOptions(manager, "GcnMatching.onnx_", &options->onnx);
  manager->AddDefaultOption("GcnMatching.onnx_batch_size",
                            &options->onnx_batch_size,
                            "images per CNN forward pass");
}

}  // namespace colmap_gcn
