#pragma once

#include <cstdint>
#include <limits>
#include <utility>

namespace colmap_gcn {

// Identifier types, as in COLMAP's util/types.h.
typedef uint32_t camera_t;
typedef uint32_t image_t;
typedef uint64_t image_pair_t;
typedef uint32_t point2D_t;
typedef uint64_t point3D_t;

const camera_t kInvalidCameraId = std::numeric_limits<camera_t>::max();
const image_t kInvalidImageId = std::numeric_limits<image_t>::max();
const image_pair_t kInvalidImagePairId =
    std::numeric_limits<image_pair_t>::max();
const point2D_t kInvalidPoint2DIdx = std::numeric_limits<point2D_t>::max();
const point3D_t kInvalidPoint3DId = std::numeric_limits<point3D_t>::max();

// An unordered image pair as produced by pair generators.
typedef std::pair<image_t, image_t> ImagePair;

}  // namespace colmap_gcn
