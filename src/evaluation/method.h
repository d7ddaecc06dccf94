#pragma once

#include <string>
#include <vector>

namespace colmap_gcn {

// One --methods entry: "exhaustive", "knn:25", "vocab_tree:25", "gcn",
// "oracle". Every method becomes a PairGenerator through
// CreatePairGenerator's options (--GcnMatching.*); the oracle is imported
// pairs (exactly the labelled matchable pairs).
struct BenchmarkMethod {
  std::string spec;     // as given, e.g. "knn:25"
  std::string pairing;  // --GcnMatching.pairing value
  int k = 0;            // retrieval depth for knn / vocab_tree, else 0

  bool IsOracle() const { return pairing == "oracle"; }
  // A folder-safe name ("knn-25").
  std::string DirName() const;
  // k capped by N - 1 (retrieval cannot return more neighbours).
  int EffectiveK(size_t num_images) const;
};

// Throws Error on an unknown pairing, a malformed spec or a bad k. A known
// pairing this build cannot create (e.g. gcn without a model) is reported
// as unavailable by the benchmark.
BenchmarkMethod ParseBenchmarkMethod(const std::string& spec);
// "none" gives no methods: scenes are only extracted and labelled.
std::vector<BenchmarkMethod> ParseBenchmarkMethods(
    const std::string& comma_list);

// The --GcnMatching.* arguments that select the method (without a program
// name). oracle_pairs_path is the labelled pairs file the oracle imports.
std::vector<std::string> GcnMatchingArguments(
    const BenchmarkMethod& method,
    size_t num_images,
    const std::string& oracle_pairs_path);

}  // namespace colmap_gcn
