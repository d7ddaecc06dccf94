#pragma once

#include <string>
#include <utility>
#include <vector>

#include "scene/database.h"

namespace colmap_gcn {
namespace test {

// Creates a COLMAP 3.8 database with one camera and the given images (name,
// descriptors); image ids are 1, 2, ... in order. Keypoints are zeros.
void CreateDescriptorDatabase(
    const std::string& path,
    const std::vector<std::pair<std::string, FeatureDescriptors>>& images);

// Replaces the descriptors of one image.
void UpdateDescriptors(const std::string& path,
                       image_t image_id,
                       const FeatureDescriptors& descriptors);

// Random SIFT-like descriptors: blob-structured uint8 rows around one of
// num_modes prototypes (so k-means has something to find).
FeatureDescriptors RandomDescriptors(int rows, int num_modes, uint32_t seed);

// A database of num_images images "<prefix><i>.jpg" whose descriptors are
// RandomDescriptors(rows, num_modes, first_seed + i).
void CreateRandomDescriptorDatabase(const std::string& path,
                                    int num_images,
                                    int rows,
                                    int num_modes,
                                    uint32_t first_seed,
                                    const std::string& prefix = "image");

}  // namespace test
}  // namespace colmap_gcn
