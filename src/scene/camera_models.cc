#include "scene/camera_models.h"

#include <array>

namespace colmap_gcn {
namespace {

struct CameraModelInfo {
  int model_id;
  const char* name;
  int num_params;
};

// Indexed by model id; the ids and parameter counts are part of COLMAP's file
// formats (cameras.bin stores the id and no parameter count), so they must
// match sensor/models.h exactly.
constexpr std::array<CameraModelInfo, 11> kCameraModels = {{
    {0, "SIMPLE_PINHOLE", 3},         // f, cx, cy
    {1, "PINHOLE", 4},                // fx, fy, cx, cy
    {2, "SIMPLE_RADIAL", 4},          // f, cx, cy, k
    {3, "RADIAL", 5},                 // f, cx, cy, k1, k2
    {4, "OPENCV", 8},                 // fx, fy, cx, cy, k1, k2, p1, p2
    {5, "OPENCV_FISHEYE", 8},         // fx, fy, cx, cy, k1, k2, k3, k4
    {6, "FULL_OPENCV", 12},           // fx, fy, cx, cy, k1..k6, p1, p2
    {7, "FOV", 5},                    // fx, fy, cx, cy, omega
    {8, "SIMPLE_RADIAL_FISHEYE", 4},  // f, cx, cy, k
    {9, "RADIAL_FISHEYE", 5},         // f, cx, cy, k1, k2
    {10, "THIN_PRISM_FISHEYE", 12},   // fx, fy, cx, cy, k1, k2, p1, p2,
                                      // k3, k4, sx1, sy1
}};

const CameraModelInfo* FindModel(int model_id) {
  if (model_id < 0 || model_id >= static_cast<int>(kCameraModels.size())) {
    return nullptr;
  }
  return &kCameraModels[model_id];
}

}  // namespace

int CameraModelNameToId(const std::string& name) {
  for (const CameraModelInfo& model : kCameraModels) {
    if (name == model.name) {
      return model.model_id;
    }
  }
  return -1;
}

std::string CameraModelIdToName(const int model_id) {
  const CameraModelInfo* model = FindModel(model_id);
  return model == nullptr ? "" : model->name;
}

int CameraModelNumParams(const int model_id) {
  const CameraModelInfo* model = FindModel(model_id);
  return model == nullptr ? -1 : model->num_params;
}

}  // namespace colmap_gcn
