#include "scene/model_writer.h"

#include <cstdint>
#include <type_traits>

#include "scene/camera_models.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace test {
namespace {

template <typename T>
void AppendBinary(const T& value, std::string* out) {
  static_assert(std::is_trivially_copyable<T>::value, "POD only");
  out->append(reinterpret_cast<const char*>(&value), sizeof(T));
}

}  // namespace

void WriteBinaryModel(const Reconstruction& model, const std::string& path) {
  CreateDirIfNotExists(path);

  std::string cameras_data;
  AppendBinary<uint64_t>(model.cameras.size(), &cameras_data);
  for (const auto& [camera_id, camera] : model.cameras) {
    if (camera.params.size() !=
        static_cast<size_t>(CameraModelNumParams(camera.model_id))) {
      ThrowError("camera ", camera_id, " has the wrong number of params");
    }
    AppendBinary<uint32_t>(camera_id, &cameras_data);
    AppendBinary<int32_t>(camera.model_id, &cameras_data);
    AppendBinary<uint64_t>(camera.width, &cameras_data);
    AppendBinary<uint64_t>(camera.height, &cameras_data);
    for (const double param : camera.params) {
      AppendBinary<double>(param, &cameras_data);
    }
  }

  std::string images_data;
  AppendBinary<uint64_t>(model.images.size(), &images_data);
  for (const auto& [image_id, image] : model.images) {
    if (image.points2D.size() != image.point3D_ids.size()) {
      ThrowError("image ", image_id, " has point arrays of different sizes");
    }
    AppendBinary<uint32_t>(image_id, &images_data);
    for (int k = 0; k < 4; ++k) {
      AppendBinary<double>(image.qvec(k), &images_data);
    }
    for (int k = 0; k < 3; ++k) {
      AppendBinary<double>(image.tvec(k), &images_data);
    }
    AppendBinary<uint32_t>(image.camera_id, &images_data);
    images_data.append(image.name.c_str(), image.name.size() + 1);
    AppendBinary<uint64_t>(image.points2D.size(), &images_data);
    for (size_t j = 0; j < image.points2D.size(); ++j) {
      AppendBinary<double>(image.points2D[j].x(), &images_data);
      AppendBinary<double>(image.points2D[j].y(), &images_data);
      AppendBinary<uint64_t>(image.point3D_ids[j], &images_data);
    }
  }

  std::string points_data;
  AppendBinary<uint64_t>(model.points3D.size(), &points_data);
  for (const auto& [point3D_id, point] : model.points3D) {
    AppendBinary<uint64_t>(point3D_id, &points_data);
    for (int k = 0; k < 3; ++k) {
      AppendBinary<double>(point.xyz(k), &points_data);
    }
    for (int k = 0; k < 3; ++k) {
      AppendBinary<uint8_t>(point.color(k), &points_data);
    }
    AppendBinary<double>(point.error, &points_data);
    AppendBinary<uint64_t>(point.track.size(), &points_data);
    for (const TrackElement& element : point.track) {
      AppendBinary<uint32_t>(element.image_id, &points_data);
      AppendBinary<uint32_t>(element.point2D_idx, &points_data);
    }
  }

  WriteFileAtomically(JoinPaths(path, "cameras.bin"), cameras_data);
  WriteFileAtomically(JoinPaths(path, "images.bin"), images_data);
  WriteFileAtomically(JoinPaths(path, "points3D.bin"), points_data);
}

}  // namespace test
}  // namespace colmap_gcn
