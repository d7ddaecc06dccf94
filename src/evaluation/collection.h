#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "pairing/pairs_io.h"
#include "scene/reconstruction.h"

namespace colmap_gcn {

// A merged photo collection (scripts/research/merge_scenes.sh) names its
// images "<scene>__<name>", so which place a photo shows is known without
// labels: pairs across scenes share nothing, and each scene's registration
// can be compared with that scene reconstructed alone.

// The scene of a merged collection's image; "" when the name has no prefix.
std::string CollectionScene(const std::string& image_name);

// The scenes of these images (their prefixes; "" for a name without one).
std::set<std::string> CollectionScenes(
    const std::vector<std::string>& image_names);

// True when every image carries a scene prefix and there are at least two
// scenes.
bool IsMergedCollection(const std::vector<std::string>& image_names);

// Pairs whose images belong to different scenes.
size_t CountCrossScenePairs(const std::vector<ImageNamePair>& pairs);

struct CollectionSceneRegistration {
  size_t num_images = 0;      // the scene's images in the collection
  size_t num_registered = 0;  // in the model that holds most of them
  size_t num_models = 0;      // models holding any of them
};

struct CollectionRegistration {
  std::map<std::string, CollectionSceneRegistration> scenes;
  size_t num_models = 0;
  // Models holding images of more than one scene: a wrong merge unless the
  // scenes really overlap.
  size_t num_mixed_models = 0;
};

// Counts, per scene, the registered images of its best model: a scene that
// the mapper splits over several models counts only its largest part, as a
// scene reconstructed alone counts only its largest model.
CollectionRegistration CountCollectionRegistration(
    const std::vector<std::string>& image_names,
    const std::vector<Reconstruction>& models);

// The same for the models a mapper run wrote to sparse_path.
CollectionRegistration ReadCollectionRegistration(
    const std::vector<std::string>& image_names,
    const std::string& sparse_path);

}  // namespace colmap_gcn
