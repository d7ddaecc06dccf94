#include "controllers/vocab_tree_pairing.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <unordered_set>

#include "retrieval/embedding_cache.h"
#include "retrieval/hash.h"
#include "scene/database_copy.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {

void VocabTreePairingOptions::Check() const {
  CHECK_OPTION_GE(k, 1);
  CHECK_OPTION_GE(num_visual_words, 0);
  CHECK_OPTION_GE(block_size, 1);
}

void VocabTreeBuildOptions::Check() const {
  CHECK_OPTION_GE(num_visual_words, 0);
  CHECK_OPTION_GE(branching, 2);
  CHECK_OPTION_GE(num_iterations, 1);
}

int AutoNumVisualWords(size_t num_descriptors) {
  size_t words = 64;
  while (words * 2 <= num_descriptors / 50 && words < 16384) words *= 2;
  return static_cast<int>(std::min(words, num_descriptors));
}

void BuildVocabTree(const ColmapRunner& colmap,
                    const std::vector<std::string>& database_paths,
                    const std::string& output_path,
                    const VocabTreeBuildOptions& options) {
  options.Check();
  if (database_paths.empty()) {
    ThrowError("no database to build a vocabulary tree from");
  }
  TemporaryDirectory temp("colmap_gcn_vocab_tree");
  const std::string database_path = JoinPaths(temp.Path(), "merged.db");
  if (database_paths.size() > 1) {
    MergeDatabases(database_paths, database_path);
  } else {
    CopyDatabase(database_paths[0], database_path);
  }
  size_t num_descriptors = 0;
  {
    const Database database(database_path);
    num_descriptors = database.NumDescriptors();
  }
  const int num_words = options.num_visual_words > 0
                            ? options.num_visual_words
                            : AutoNumVisualWords(num_descriptors);
  if (num_descriptors < static_cast<size_t>(num_words) || num_words < 2) {
    ThrowError("a vocabulary tree of ",
               num_words,
               " words needs at least as many descriptors; the databases "
               "have ",
               num_descriptors);
  }
  // COLMAP writes the tree directly; build into a temporary file so an
  // interrupted build never leaves a truncated tree at output_path.
  const std::string tmp_tree = JoinPaths(temp.Path(), "tree.bin");
  colmap.Run("vocab_tree_builder",
             {"--database_path",
              database_path,
              "--vocab_tree_path",
              tmp_tree,
              "--num_visual_words",
              std::to_string(num_words),
              "--branching",
              std::to_string(std::min(options.branching, num_words)),
              "--num_iterations",
              std::to_string(options.num_iterations)});
  // COLMAP writes the tree unchecked; on a full disk it is missing or empty.
  std::error_code ec;
  if (!ExistsFile(tmp_tree) || std::filesystem::file_size(tmp_tree, ec) == 0) {
    ThrowError("colmap vocab_tree_builder exited 0 but wrote no tree to ",
               tmp_tree,
               " (is the disk full?)");
  }
  std::filesystem::copy_file(tmp_tree,
                             output_path + ".tmp",
                             std::filesystem::copy_options::overwrite_existing);
  std::filesystem::rename(output_path + ".tmp", output_path);
}

std::vector<ImagePair> ParseVocabTreeRetrieval(
    const std::string& output,
    const std::vector<DatabaseImage>& images,
    int k) {
  std::map<std::string, image_t> ids_by_name;
  std::unordered_set<image_t> known_ids;
  for (const DatabaseImage& image : images) {
    ids_by_name[image.name] = image.image_id;
    known_ids.insert(image.image_id);
  }
  static const std::regex kQuery(R"(^Querying for image (.*) \[\d+/\d+\])");
  static const std::regex kHit(R"(^\s*image_id=(\d+), image_name=.*, score=)");
  std::vector<ImagePair> pairs;
  std::unordered_set<image_pair_t> seen;
  image_t query = kInvalidImageId;
  int num_hits = 0;
  std::istringstream stream(output);
  std::string line;
  std::smatch match;
  while (std::getline(stream, line)) {
    if (std::regex_search(line, match, kQuery)) {
      const auto it = ids_by_name.find(match[1].str());
      if (it == ids_by_name.end()) {
        ThrowError("vocab_tree_retriever queried unknown image ",
                   match[1].str());
      }
      query = it->second;
      num_hits = 0;
    } else if (std::regex_search(line, match, kHit)) {
      if (query == kInvalidImageId) {
        ThrowError("unexpected vocab_tree_retriever output: ", line);
      }
      const image_t hit = static_cast<image_t>(std::stoul(match[1].str()));
      if (known_ids.count(hit) == 0) {
        ThrowError("vocab_tree_retriever returned unknown image id ", hit);
      }
      // The query is usually, not always, its own top hit.
      if (hit == query || num_hits >= k) continue;
      ++num_hits;
      if (seen.insert(ImagePairToPairId(query, hit)).second) {
        pairs.emplace_back(query, hit);
      }
    }
  }
  return pairs;
}

namespace {

// Key of everything a self-built tree depends on.
std::string TreeKey(const Database& database, int num_visual_words) {
  uint64_t key = HashCombine(0x7eee, static_cast<uint64_t>(num_visual_words));
  for (const DatabaseImage& image : database.ReadAllImages()) {
    key = HashCombine(
        key,
        ImageFeatureKey(image.name, database.ReadDescriptors(image.image_id)));
  }
  return std::to_string(key);
}

}  // namespace

std::string BuildDatabaseVocabTree(const Database& database,
                                   const ColmapRunner& colmap,
                                   const VocabTreePairingOptions& options) {
  const std::string tree_path = database.Path() + ".gcn-vocab-tree.bin";
  const std::string key_path = tree_path + ".key";
  const std::string key = TreeKey(database, options.num_visual_words);
  if (!ExistsFile(tree_path) || !ExistsFile(key_path) ||
      StringTrim(ReadTextFile(key_path)) != key) {
    VocabTreeBuildOptions build_options;
    build_options.num_visual_words = options.num_visual_words;
    BuildVocabTree(colmap, {database.Path()}, tree_path, build_options);
    WriteFileAtomically(key_path, key + "\n");
  }
  return tree_path;
}

VocabTreePairGenerator::VocabTreePairGenerator(
    const VocabTreePairingOptions& options,
    const Database& database,
    const ColmapRunner& colmap)
    : options_(options) {
  options_.Check();
  std::string tree_path = options_.vocab_tree_path;
  if (tree_path.empty()) {
    tree_path = BuildDatabaseVocabTree(database, colmap, options_);
  } else if (!ExistsFile(tree_path)) {
    ThrowError("vocabulary tree ", tree_path, " does not exist");
  }
  const std::vector<DatabaseImage> images = database.ReadAllImages();
  const int k = std::min<int>(options_.k, static_cast<int>(images.size()) - 1);
  if (k <= 0) return;
  // COLMAP opens databases read-write even to read; it works on a snapshot
  // so that no WAL file of its appears beside the user's database.
  TemporaryDirectory temp("colmap_gcn_vocab_tree");
  const std::string snapshot = JoinPaths(temp.Path(), "database.db");
  CopyDatabase(database.Path(), snapshot);
  const std::string output = colmap.Run("vocab_tree_retriever",
                                        {"--database_path",
                                         snapshot,
                                         "--vocab_tree_path",
                                         tree_path,
                                         "--num_images",
                                         std::to_string(k + 1)});
  image_pairs_ = ParseVocabTreeRetrieval(output, images, k);
}

void VocabTreePairGenerator::Reset() { pair_idx_ = 0; }

bool VocabTreePairGenerator::HasFinished() const {
  return pair_idx_ >= image_pairs_.size();
}

std::vector<ImagePair> VocabTreePairGenerator::Next() {
  return NextPairBlock(image_pairs_, options_.block_size, &pair_idx_);
}

PairGeneratorSpec<VocabTreePairingOptions> VocabTreePairGeneratorSpec() {
  PairGeneratorSpec<VocabTreePairingOptions> spec;
  spec.name = "vocab_tree";
  spec.add_options = [](OptionManager* manager,
                        VocabTreePairingOptions* options) {
    manager->AddDefaultOption("GcnMatching.k",
                              &options->k,
                              "neighbours per image for knn | vocab_tree");
    manager->AddDefaultOption(
        "GcnMatching.vocab_tree_path",
        &options->vocab_tree_path,
        "vocabulary tree; empty: built from this database");
  };
  const auto colmap = [](const PairGeneratorContext& context) {
    ColmapRunnerOptions runner_options;
    runner_options.log_path = context.colmap_log_path.empty()
                                  ? context.database.Path() + ".colmap.log"
                                  : context.colmap_log_path;
    runner_options.verbose = context.verbose;
    return ColmapRunner(runner_options);
  };
  spec.create = [colmap](const VocabTreePairingOptions& options,
                         const PairGeneratorContext& context) {
    return std::make_unique<VocabTreePairGenerator>(
        options, context.database, colmap(context));
  };
  // A user downloads a tree; the benchmark builds this database's own
  // beforehand, so that vocab_tree's pairing time is the retrieval alone.
  spec.prepare = [colmap](VocabTreePairingOptions* options,
                          const PairGeneratorContext& context) {
    if (options->vocab_tree_path.empty()) {
      options->vocab_tree_path =
          BuildDatabaseVocabTree(context.database, colmap(context), *options);
    }
  };
  spec.depth = [](VocabTreePairingOptions* options) { return &options->k; };
  return spec;
}

}  // namespace colmap_gcn
