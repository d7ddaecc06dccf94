#pragma once

namespace colmap_gcn {

// `colmap gcn_merge_databases --database_paths a.db,b.db --output_path
// merged.db [--name_prefixes a__,b__]`: one COLMAP 3.8 database with every
// input's cameras, images, keypoints and descriptors (MergeDatabases), for
// merged photo collections (scripts/research/merge_scenes.sh).
int RunGcnMergeDatabases(int argc, char** argv);

}  // namespace colmap_gcn
