#pragma once

#include <any>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pairing/pair_generator_spec.h"
#include "pairing/pairing.h"
#include "util/error.h"

namespace colmap_gcn {

// The options of every registered generator, one typed struct each with its
// defaults, found by generator name:
// `options.Get<KnnPairingOptions>("knn").k = 5`.
class PairGeneratorOptions {
 public:
  template <typename Options>
  Options& Get(const std::string& name);
  template <typename Options>
  const Options& Get(const std::string& name) const;

 private:
  friend class PairGeneratorRegistry;
  std::any& Any(const std::string& name);
  const std::any& Any(const std::string& name) const;

  std::map<std::string, std::any> options_;
};

// Pair generators by --GcnMatching.pairing name. Each registers once with a
// PairGeneratorSpec; PairGenerators() (controllers/pair_generators.h) is the
// registry of this build, through which `gcn_matcher`, `gcn_reconstructor`
// and `gcn_benchmark` create generators.
class PairGeneratorRegistry {
 public:
  template <typename Options>
  void Register(PairGeneratorSpec<Options> spec);

  // In registration order; the first is the default pairing.
  std::vector<std::string> Names() const;
  bool Has(const std::string& name) const;

  // Every generator's options at their defaults.
  PairGeneratorOptions DefaultOptions() const;

  // Binds every generator's --GcnMatching.* flags to *options.
  void AddOptions(OptionManager* manager, PairGeneratorOptions* options) const;

  // Checks generator `name`'s options (OptionError naming the field); an
  // unknown name is an Error listing the known ones.
  void Check(const std::string& name,
             const PairGeneratorOptions& options) const;

  // Checks, then builds generator `name`.
  std::unique_ptr<PairGenerator> Create(
      const std::string& name,
      const PairGeneratorOptions& options,
      const PairGeneratorContext& context) const;

  // The field of `name`'s options that gcn_benchmark's "<name>:<k>" sets,
  // or nullptr when the generator takes no k.
  int* Depth(const std::string& name, PairGeneratorOptions* options) const;
  bool TakesDepth(const std::string& name) const;

  // Whether gcn_benchmark offers `name` as a method.
  bool IsBenchmarkMethod(const std::string& name) const;

  // Whether `name` chooses its pairs from verifications, round by round.
  bool UsesVerification(const std::string& name) const;

  // Runs `name`'s prepare step (PairGeneratorSpec::prepare) on *options;
  // false when it has none.
  bool Prepare(const std::string& name,
               PairGeneratorOptions* options,
               const PairGeneratorContext& context) const;

 private:
  struct Entry {
    std::string name;
    std::function<std::any()> make_options;
    std::function<void(OptionManager*, std::any*)> add_options;
    std::function<void(const std::any&)> check;
    std::function<std::unique_ptr<PairGenerator>(const std::any&,
                                                 const PairGeneratorContext&)>
        create;
    std::function<int*(std::any*)> depth;
    bool benchmark_method = true;
    bool uses_verification = false;
    std::function<void(std::any*, const PairGeneratorContext&)> prepare;
  };

  const Entry& Find(const std::string& name) const;

  std::vector<Entry> entries_;
};

template <typename Options>
Options& PairGeneratorOptions::Get(const std::string& name) {
  Options* options = std::any_cast<Options>(&Any(name));
  THROW_CHECK(options != nullptr);
  return *options;
}

template <typename Options>
const Options& PairGeneratorOptions::Get(const std::string& name) const {
  const Options* options = std::any_cast<Options>(&Any(name));
  THROW_CHECK(options != nullptr);
  return *options;
}

template <typename Options>
void PairGeneratorRegistry::Register(PairGeneratorSpec<Options> spec) {
  THROW_CHECK(!spec.name.empty() && !Has(spec.name) && spec.create);
  Entry entry;
  entry.name = spec.name;
  entry.make_options = [] { return std::any(Options()); };
  entry.add_options = [add = spec.add_options](OptionManager* manager,
                                               std::any* options) {
    if (add) add(manager, std::any_cast<Options>(options));
  };
  entry.check = [check = spec.check](const std::any& any) {
    const Options& options = *std::any_cast<Options>(&any);
    if (check) {
      check(options);
    } else {
      options.Check();
    }
  };
  entry.create = [create = spec.create](const std::any& options,
                                        const PairGeneratorContext& context) {
    return create(*std::any_cast<Options>(&options), context);
  };
  if (spec.depth) {
    entry.depth = [depth = spec.depth](std::any* options) {
      return depth(std::any_cast<Options>(options));
    };
  }
  if (spec.prepare) {
    entry.prepare = [prepare = spec.prepare](
                        std::any* options,
                        const PairGeneratorContext& context) {
      prepare(std::any_cast<Options>(options), context);
    };
  }
  entry.benchmark_method = spec.benchmark_method;
  entry.uses_verification = spec.uses_verification;
  entries_.push_back(std::move(entry));
}

}  // namespace colmap_gcn
