#pragma once

#include "pairing/pair_generator_registry.h"

namespace colmap_gcn {

// Every pair generator of this build, one registration line each
// (pair_generators.cc); the first is the default pairing. The list is
// assembled here, above src/pairing/, because the vocabulary tree and the
// adaptive generators run COLMAP or live beside the controllers.
const PairGeneratorRegistry& PairGenerators();

}  // namespace colmap_gcn
