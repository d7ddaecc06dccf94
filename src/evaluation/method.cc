#include "evaluation/method.h"

#include <algorithm>

#include "util/error.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

// The option that sets the retrieval depth of the k-based pairings (the
// retrieval module's flag); nullptr for pairings without k.
const char* KOptionName(const std::string& pairing) {
  if (pairing == "knn" || pairing == "vocab_tree") return "--GcnMatching.k";
  return nullptr;
}

}  // namespace

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
  static const std::vector<std::string> kPairings = {
      "exhaustive", "knn", "vocab_tree", "gcn", "oracle"};
  if (!method.pairing.empty() &&
      std::find(kPairings.begin(), kPairings.end(), method.pairing) ==
          kPairings.end()) {
    ThrowError("bad method \"",
               spec,
               "\" in --methods: must be one of "
               "exhaustive|knn:<k>|vocab_tree:<k>|gcn|oracle");
  }
  const bool k_based = KOptionName(method.pairing) != nullptr;
  if (fields.size() > 2 || (fields.size() == 2 && !k_based)) {
    ThrowError(
        "bad method \"", spec, "\": only knn:<k> and vocab_tree:<k> take a k");
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

std::vector<std::string> GcnMatchingArguments(
    const BenchmarkMethod& method,
    size_t num_images,
    const std::string& oracle_pairs_path) {
  if (method.IsOracle()) {
    return {"--GcnMatching.pairing",
            "imported",
            "--GcnMatching.match_list_path",
            oracle_pairs_path};
  }
  std::vector<std::string> args = {"--GcnMatching.pairing", method.pairing};
  if (const char* k_option = KOptionName(method.pairing)) {
    args.push_back(k_option);
    args.push_back(std::to_string(method.EffectiveK(num_images)));
  }
  return args;
}

}  // namespace colmap_gcn
