#pragma once

#include "pairing/pair_generator_registry.h"

namespace colmap_gcn {

// Every pair generator of this build, one registration line each
// (pair_generators.cc); a flag several generators bind shows the first's
// default in -h. The list is
// assembled here, above src/pairing/, because the vocabulary tree and the
// adaptive generators run COLMAP or live beside the controllers.
const PairGeneratorRegistry& PairGenerators();

// gcn_matcher's and gcn_reconstructor's pairing: the GCN's candidates cut by
// verification round by round; its F was above the single-shot GCN's on
// nine of ten labelled scenes and its mean F above the per-scene best fixed
// k (docs/benchmarks.md, "The choice").
inline constexpr char kDefaultPairing[] = "adaptive";

}  // namespace colmap_gcn
