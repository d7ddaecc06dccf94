#include "pairing/pair_generator_registry.h"

#include "util/string.h"

namespace colmap_gcn {

std::any& PairGeneratorOptions::Any(const std::string& name) {
  const auto it = options_.find(name);
  if (it == options_.end()) ThrowError("no options for pair generator ", name);
  return it->second;
}

const std::any& PairGeneratorOptions::Any(const std::string& name) const {
  const auto it = options_.find(name);
  if (it == options_.end()) ThrowError("no options for pair generator ", name);
  return it->second;
}

std::vector<std::string> PairGeneratorRegistry::Names() const {
  std::vector<std::string> names;
  for (const Entry& entry : entries_) names.push_back(entry.name);
  return names;
}

bool PairGeneratorRegistry::Has(const std::string& name) const {
  for (const Entry& entry : entries_) {
    if (entry.name == name) return true;
  }
  return false;
}

const PairGeneratorRegistry::Entry& PairGeneratorRegistry::Find(
    const std::string& name) const {
  for (const Entry& entry : entries_) {
    if (entry.name == name) return entry;
  }
  ThrowError("unknown pair generator \"",
             name,
             "\": must be one of ",
             StringJoin(Names(), "|"));
}

PairGeneratorOptions PairGeneratorRegistry::DefaultOptions() const {
  PairGeneratorOptions options;
  for (const Entry& entry : entries_) {
    options.options_.emplace(entry.name, entry.make_options());
  }
  return options;
}

void PairGeneratorRegistry::AddOptions(OptionManager* manager,
                                       PairGeneratorOptions* options) const {
  for (const Entry& entry : entries_) {
    entry.add_options(manager, &options->Any(entry.name));
  }
}

void PairGeneratorRegistry::Check(const std::string& name,
                                  const PairGeneratorOptions& options) const {
  Find(name).check(options.Any(name));
}

std::unique_ptr<PairGenerator> PairGeneratorRegistry::Create(
    const std::string& name,
    const PairGeneratorOptions& options,
    const PairGeneratorContext& context) const {
  const Entry& entry = Find(name);
  entry.check(options.Any(name));
  return entry.create(options.Any(name), context);
}

int* PairGeneratorRegistry::Depth(const std::string& name,
                                  PairGeneratorOptions* options) const {
  const Entry& entry = Find(name);
  return entry.depth ? entry.depth(&options->Any(name)) : nullptr;
}

bool PairGeneratorRegistry::TakesDepth(const std::string& name) const {
  return static_cast<bool>(Find(name).depth);
}

bool PairGeneratorRegistry::IsBenchmarkMethod(const std::string& name) const {
  return Find(name).benchmark_method;
}

bool PairGeneratorRegistry::UsesVerification(const std::string& name) const {
  return Find(name).uses_verification;
}

bool PairGeneratorRegistry::Prepare(const std::string& name,
                                    PairGeneratorOptions* options,
                                    const PairGeneratorContext& context) const {
  const Entry& entry = Find(name);
  if (!entry.prepare) return false;
  entry.prepare(&options->Any(name), context);
  return true;
}

}  // namespace colmap_gcn
