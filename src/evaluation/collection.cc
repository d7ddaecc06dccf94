#include "evaluation/collection.h"

#include <algorithm>

#include "scene/reconstruction_stats.h"

namespace colmap_gcn {

std::string CollectionScene(const std::string& image_name) {
  const size_t pos = image_name.find("__");
  return pos == std::string::npos ? "" : image_name.substr(0, pos);
}

std::set<std::string> CollectionScenes(
    const std::vector<std::string>& image_names) {
  std::set<std::string> scenes;
  for (const std::string& name : image_names) {
    scenes.insert(CollectionScene(name));
  }
  return scenes;
}

bool IsMergedCollection(const std::vector<std::string>& image_names) {
  const std::set<std::string> scenes = CollectionScenes(image_names);
  return scenes.size() >= 2 && scenes.count("") == 0;
}

size_t CountCrossScenePairs(const std::vector<ImageNamePair>& pairs) {
  size_t count = 0;
  for (const auto& [name1, name2] : pairs) {
    if (CollectionScene(name1) != CollectionScene(name2)) ++count;
  }
  return count;
}

CollectionRegistration CountCollectionRegistration(
    const std::vector<std::string>& image_names,
    const std::vector<Reconstruction>& models) {
  CollectionRegistration registration;
  registration.num_models = models.size();
  for (const std::string& name : image_names) {
    ++registration.scenes[CollectionScene(name)].num_images;
  }
  for (const Reconstruction& model : models) {
    std::map<std::string, size_t> per_scene;
    for (const auto& [image_id, image] : model.images) {
      const auto scene = registration.scenes.find(CollectionScene(image.name));
      // An image the database does not list belongs to no scene here.
      if (scene != registration.scenes.end()) ++per_scene[scene->first];
    }
    if (per_scene.size() > 1) ++registration.num_mixed_models;
    for (const auto& [scene, count] : per_scene) {
      CollectionSceneRegistration& entry = registration.scenes.at(scene);
      ++entry.num_models;
      entry.num_registered = std::max(entry.num_registered, count);
    }
  }
  return registration;
}

CollectionRegistration ReadCollectionRegistration(
    const std::vector<std::string>& image_names,
    const std::string& sparse_path) {
  std::vector<Reconstruction> models;
  for (const std::string& model_path : ListSparseModels(sparse_path)) {
    models.emplace_back();
    models.back().Read(model_path);
  }
  return CountCollectionRegistration(image_names, models);
}

}  // namespace colmap_gcn
