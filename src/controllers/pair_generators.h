#pragma once

#include "pairing/pair_generator_registry.h"

namespace colmap_gcn {

// Every pair generator of this build, one registration line each
// (pair_generators.cc). The list is assembled here, above src/pairing/,
// because the vocabulary tree and the adaptive generators run COLMAP or
// live beside the controllers. A flag that several generators share (e.g.
// --GcnMatching.k) shows the first registered one's default in -h.
const PairGeneratorRegistry& PairGenerators();

// gcn_matcher's and gcn_reconstructor's pairing when none is given: the
// GCN's candidates chosen in rounds from COLMAP's verification, measured
// against the single-shot GCN and fixed k in docs/benchmarks.md ("Default
// pairing").
inline constexpr char kDefaultPairing[] = "adaptive";

}  // namespace colmap_gcn
