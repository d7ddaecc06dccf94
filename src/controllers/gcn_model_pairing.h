#pragma once

#include <memory>
#include <string>
#include <vector>

#include "gcn/gcn_model.h"
#include "gcn/gcn_pair_generator.h"
#include "retrieval/knn.h"
#include "scene/database.h"

namespace colmap_gcn {

// The model `gcn_matcher` uses when none is given: $COLMAP_GCN_MODEL, else
// the one installed beside the front end (../share/colmap-gcn/), else the
// one in the source tree (colmap_gcn/models/default.gcnmodel). Empty if
// there is none.
std::string DefaultGcnModelPath();

// The global descriptors the model was trained on, one row per database
// image (ascending image id, in *image_ids): the model's own VLAD embedding
// (cached beside the database, keyed on features and model), or, for a
// model trained on imported descriptors, those in descriptor_path. Throws
// Error on a dimension or type mismatch.
EmbeddingMatrix ComputeModelEmbeddings(const GcnModel& model,
                                       const Database& database,
                                       const std::string& descriptor_path,
                                       int num_threads,
                                       std::vector<image_t>* image_ids);

}  // namespace colmap_gcn
