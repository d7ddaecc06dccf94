#pragma once

#include <functional>
#include <memory>
#include <string>

#include "scene/database.h"

namespace colmap_gcn {

class OptionManager;
class PairGenerator;

// What a generator's Create gets besides its options: the database whose
// images are paired, and, for generators that run COLMAP themselves
// (vocab_tree), where its output is logged.
struct PairGeneratorContext {
  explicit PairGeneratorContext(const Database& database)
      : database(database) {}

  const Database& database;

  // Log of COLMAP's full output and whether to show it all.
  std::string colmap_log_path = "";
  bool verbose = false;
};

// A pair generator as it registers with a PairGeneratorRegistry
// (pairing/pair_generator_registry.h; this build's list is PairGenerators()
// in controllers/pair_generators.h), with its own Options struct (commented
// defaults, Check()):
//   name        the --GcnMatching.pairing value;
//   add_options binds its --GcnMatching.* flags to the fields of *options (a
//               flag several generators share, such as --GcnMatching.k, is
//               bound by each of them);
//   check       validates the options when the generator is chosen (null:
//               options.Check());
//   create      builds it from valid options;
//   depth       the field `gcn_benchmark`'s "<name>:<k>" sets (null: the
//               method takes no k);
//   benchmark_method  whether gcn_benchmark offers it as a --methods entry
//               (false for generators that need a user's file).
//   uses_verification  whether its pairs exist only round by round after
//               matching (adaptive, graphmatch): nothing to export up front.
//   prepare     the work a user does once, before pairing, and would
//               otherwise download (vocab_tree: building the tree); it may
//               set *options (the tree's path). gcn_benchmark runs it
//               outside the pairing time; null: nothing to prepare.
template <typename Options>
struct PairGeneratorSpec {
  std::string name;
  std::function<void(OptionManager* manager, Options* options)> add_options;
  std::function<void(const Options& options)> check;
  std::function<std::unique_ptr<PairGenerator>(
      const Options& options, const PairGeneratorContext& context)>
      create;
  std::function<int*(Options* options)> depth;
  bool benchmark_method = true;
  bool uses_verification = false;
  std::function<void(Options* options, const PairGeneratorContext& context)>
      prepare;
};

}  // namespace colmap_gcn
