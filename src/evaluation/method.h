#pragma once

#include <string>
#include <vector>

namespace colmap_gcn {

// One --methods entry: a registered pair generator (PairGenerators()),
// "<name>:<k>" for those that take a retrieval depth ("knn:25",
// "vocab_tree:25"), or "oracle": imported pairs, exactly the labelled
// matchable ones.
struct BenchmarkMethod {
  std::string spec;     // as given, e.g. "knn:25"
  std::string pairing;  // generator name, or "oracle"
  int k = 0;            // retrieval depth of "<name>:<k>", else 0

  bool IsOracle() const { return pairing == "oracle"; }
  // A folder-safe name ("knn-25").
  std::string DirName() const;
  // k capped by N - 1 (retrieval cannot return more neighbours).
  int EffectiveK(size_t num_images) const;
};

// What --methods accepts, from PairGenerators(): each benchmark method as
// "<name>" or "<name>:<k>" in the order of the paper's tables, then "oracle".
std::vector<std::string> BenchmarkMethodChoices();
// The help text of gcn_benchmark's --methods.
std::string BenchmarkMethodsHelp();

// Throws Error on an unknown pairing, a malformed spec or a bad k. A known
// pairing this build cannot create (e.g. gcn without a model) is reported
// as unavailable by the benchmark.
BenchmarkMethod ParseBenchmarkMethod(const std::string& spec);
// "none" gives no methods: scenes are only extracted and labelled.
std::vector<BenchmarkMethod> ParseBenchmarkMethods(
    const std::string& comma_list);

}  // namespace colmap_gcn
