#pragma once

namespace colmap_gcn {

// `colmap gcn_embedding_trainer --database_paths a.db,b.db --output_path
// vlad.bin`: trains the VLAD codebook and PCA-whitening on the descriptors of
// the given databases.
int RunGcnEmbeddingTrainer(int argc, char** argv);

}  // namespace colmap_gcn
