#include "controllers/pair_generators.h"

#include "controllers/adaptive_pairing.h"
#include "controllers/vocab_tree_pairing.h"
#include "pairing/exhaustive_pairing.h"
#include "pairing/gcn_model_pairing.h"
#include "pairing/imported_pairing.h"
#include "pairing/knn_pairing.h"
#include "pairing/sequential_pairing.h"

namespace colmap_gcn {

const PairGeneratorRegistry& PairGenerators() {
  static const PairGeneratorRegistry registry = [] {
    PairGeneratorRegistry generators;
    // One line per generator; kDefaultPairing is among them.
    generators.Register(GcnModelPairGeneratorSpec());
    generators.Register(ExhaustivePairGeneratorSpec());
    generators.Register(ImportedPairGeneratorSpec());
    generators.Register(KnnPairGeneratorSpec());
    generators.Register(VocabTreePairGeneratorSpec());
    generators.Register(SequentialPairGeneratorSpec());
    generators.Register(AdaptivePairGeneratorSpec());
    generators.Register(AdaptiveRecallPairGeneratorSpec());
    generators.Register(GraphMatchPairGeneratorSpec());
    return generators;
  }();
  return registry;
}

}  // namespace colmap_gcn
