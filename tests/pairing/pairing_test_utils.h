#pragma once

#include <string>
#include <vector>

#include "scene/database.h"

namespace colmap_gcn {
namespace test {

// Database images with the given ids, named "img<id>.jpg".
inline std::vector<DatabaseImage> MakeImages(const std::vector<image_t>& ids) {
  std::vector<DatabaseImage> images;
  for (const image_t id : ids) {
    DatabaseImage image;
    image.image_id = id;
    image.name = "img" + std::to_string(id) + ".jpg";
    images.push_back(image);
  }
  return images;
}

}  // namespace test
}  // namespace colmap_gcn
