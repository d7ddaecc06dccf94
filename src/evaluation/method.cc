#include "evaluation/method.h"

#include <algorithm>

#include "controllers/pair_generators.h"
#include "util/error.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

// "<name>" or "<name>:<k>".
std::string MethodSyntax(const std::string& name) {
  return PairGenerators().TakesDepth(name) ? name + ":<k>" : name;
}

// The generators offered as methods, listed as the paper's tables order
// them: the baselines, then the default generator (the GCN), then the
// oracle.
std::vector<std::string> MethodNames() {
  const PairGeneratorRegistry& registry = PairGenerators();
  const std::vector<std::string> names = registry.Names();
  std::vector<std::string> methods;
  for (size_t i = 1; i < names.size(); ++i) {
    if (registry.IsBenchmarkMethod(names[i])) methods.push_back(names[i]);
  }
  if (registry.IsBenchmarkMethod(names.front())) {
    methods.push_back(names.front());
  }
  return methods;
}

}  // namespace

std::vector<std::string> BenchmarkMethodChoices() {
  std::vector<std::string> choices;
  for (const std::string& name : MethodNames()) {
    choices.push_back(MethodSyntax(name));
  }
  choices.push_back("oracle");
  return choices;
}

std::string BenchmarkMethodsHelp() {
  return "comma list of " + StringJoin(BenchmarkMethodChoices(), " | ") +
         " (oracle: the labelled matchable pairs); none: features and labels "
         "only (for gcn_train)";
}

std::string BenchmarkMethod::DirName() const {
  return k > 0 ? pairing + "-" + std::to_string(k) : pairing;
}

int BenchmarkMethod::EffectiveK(size_t num_images) const {
  if (k <= 0) return 0;
  return std::min<int>(k, static_cast<int>(num_images) - 1);
}

BenchmarkMethod ParseBenchmarkMethod(const std::string& spec) {
  BenchmarkMethod method;
  method.spec = spec;
  const std::vector<std::string> fields = StringSplit(spec, ":");
  method.pairing = fields[0];
  const std::vector<std::string> names = MethodNames();
  if (!method.pairing.empty() && !method.IsOracle() &&
      std::find(names.begin(), names.end(), method.pairing) == names.end()) {
    ThrowError("bad method \"",
               spec,
               "\" in --methods: must be one of ",
               StringJoin(BenchmarkMethodChoices(), "|"));
  }
  const bool k_based = !method.IsOracle() && !method.pairing.empty() &&
                       PairGenerators().TakesDepth(method.pairing);
  if (fields.size() > 2 || (fields.size() == 2 && !k_based)) {
    std::vector<std::string> k_methods;
    for (const std::string& name : names) {
      if (PairGenerators().TakesDepth(name))
        k_methods.push_back(MethodSyntax(name));
    }
    ThrowError("bad method \"",
               spec,
               "\": only ",
               StringJoin(k_methods, " and "),
               " take a k");
  }
  if (k_based) {
    if (fields.size() != 2) {
      ThrowError(
          "method \"", spec, "\" needs a k, e.g. ", method.pairing, ":25");
    }
    try {
      method.k = std::stoi(fields[1]);
    } catch (const std::exception&) {
      method.k = 0;
    }
    if (method.k <= 0 || std::to_string(method.k) != StringTrim(fields[1])) {
      ThrowError("bad k in method \"", spec, "\": must be an integer >= 1");
    }
  } else if (method.pairing.empty()) {
    ThrowError("empty method in --methods");
  }
  return method;
}

std::vector<BenchmarkMethod> ParseBenchmarkMethods(
    const std::string& comma_list) {
  std::vector<BenchmarkMethod> methods;
  // Features and labels only: the scenes `colmap gcn_train` reads.
  if (StringTrim(comma_list) == "none") return methods;
  for (const std::string& trimmed : SplitCommaList(comma_list)) {
    methods.push_back(ParseBenchmarkMethod(trimmed));
    for (size_t i = 0; i + 1 < methods.size(); ++i) {
      if (methods[i].DirName() == methods.back().DirName()) {
        ThrowError("method ", trimmed, " given twice in --methods");
      }
    }
  }
  if (methods.empty()) ThrowError("--methods names no method");
  return methods;
}

}  // namespace colmap_gcn
