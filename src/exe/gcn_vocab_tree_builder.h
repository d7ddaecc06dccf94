#pragma once

namespace colmap_gcn {

// `colmap gcn_vocab_tree_builder --database_paths a.db,b.db --output_path
// tree.bin [--num_visual_words W]`: COLMAP's vocab_tree_builder over one or
// several databases (merged first).
int RunGcnVocabTreeBuilder(int argc, char** argv);

}  // namespace colmap_gcn
