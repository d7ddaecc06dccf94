#pragma once

#include <string>

namespace colmap_gcn {

// COLMAP's camera model ids, names and parameter counts (sensor/models.h).
// Returns -1 / "" for unknown models.
int CameraModelNameToId(const std::string& name);
std::string CameraModelIdToName(int model_id);
int CameraModelNumParams(int model_id);

}  // namespace colmap_gcn
