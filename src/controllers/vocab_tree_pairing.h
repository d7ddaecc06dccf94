#pragma once

#include <string>
#include <vector>

#include "controllers/colmap_runner.h"
#include "pairing/pair_generator_spec.h"
#include "pairing/pairing.h"
#include "scene/database.h"

namespace colmap_gcn {

struct VocabTreePairingOptions {
  // Neighbours retrieved per image (capped at N - 1). COLMAP returns the
  // query itself among its hits, so k + 1 images are requested.
  int k = 25;

  // A tree from `colmap gcn_vocab_tree_builder` (or vocab_tree_builder).
  // Empty: build one from the target database itself, cached as
  // "<database>.gcn-vocab-tree.bin" and rebuilt when its features change.
  std::string vocab_tree_path = "";

  // Visual words of a tree built here; 0 chooses from the number of
  // descriptors (AutoNumVisualWords).
  int num_visual_words = 0;

  // Number of image pairs in one block.
  int block_size = 1225;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// Visual words for a tree built from num_descriptors descriptors: about one
// word per 50 descriptors, a power of two in [64, 16384], never more than
// the descriptors (vocab_tree_builder aborts otherwise). Building is the
// slow part (16384 words from 1.2M descriptors: ~9 min on 2 cores).
int AutoNumVisualWords(size_t num_descriptors);

struct VocabTreeBuildOptions {
  // 0: AutoNumVisualWords of the merged descriptors.
  int num_visual_words = 0;

  // Branching factor of the tree (COLMAP's default is 256); capped by the
  // number of words.
  int branching = 256;

  // Lloyd iterations of COLMAP's hierarchical k-means.
  int num_iterations = 11;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// Builds a vocabulary tree with COLMAP's vocab_tree_builder from the
// descriptors of one or more databases. Several databases (COLMAP 3.8
// schema) are first merged into a temporary database, image names prefixed
// with the database's position so they stay unique.
void BuildVocabTree(const ColmapRunner& colmap,
                    const std::vector<std::string>& database_paths,
                    const std::string& output_path,
                    const VocabTreeBuildOptions& options);

// The tree of a VocabTreePairGenerator without vocab_tree_path: built from
// the database's own descriptors with options.num_visual_words, cached as
// "<database>.gcn-vocab-tree.bin" and rebuilt when its features change.
// Returns its path.
std::string BuildDatabaseVocabTree(const Database& database,
                                   const ColmapRunner& colmap,
                                   const VocabTreePairingOptions& options);

// Parses vocab_tree_retriever output ("Querying for image NAME [i/N]" then
// "  image_id=ID, image_name=NAME, score=S" lines) into unordered pairs: per
// query its best k hits other than itself, deduplicated, oriented (query,
// hit) as first seen. Unknown names or ids throw Error.
std::vector<ImagePair> ParseVocabTreeRetrieval(
    const std::string& output, const std::vector<DatabaseImage>& images, int k);

// COLMAP's vocabulary-tree retrieval as a pair generator: the retrieval is
// run once (`colmap vocab_tree_retriever`) in the constructor.
class VocabTreePairGenerator : public PairGenerator {
 public:
  using PairOptions = VocabTreePairingOptions;

  VocabTreePairGenerator(const VocabTreePairingOptions& options,
                         const Database& database,
                         const ColmapRunner& colmap);

  void Reset() override;
  bool HasFinished() const override;
  std::vector<ImagePair> Next() override;

 private:
  const VocabTreePairingOptions options_;
  std::vector<ImagePair> image_pairs_;
  size_t pair_idx_ = 0;
};

// --GcnMatching.pairing vocab_tree (--GcnMatching.k, vocab_tree_path).
PairGeneratorSpec<VocabTreePairingOptions> VocabTreePairGeneratorSpec();

}  // namespace colmap_gcn
