#pragma once

#include <string>

#include "scene/reconstruction.h"

namespace colmap_gcn {
namespace test {

// Writes a model in COLMAP's binary format (cameras.bin, images.bin,
// points3D.bin; the folder is created if needed), the format COLMAP's
// mapper writes and Reconstruction::ReadBinary reads. Throws Error on a
// camera whose parameter count does not fit its model or an image whose
// point arrays differ in length.
void WriteBinaryModel(const Reconstruction& model, const std::string& path);

}  // namespace test
}  // namespace colmap_gcn
