#include "evaluation/bundler.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "scene/camera_models.h"
#include "util/error.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

// Bundler's camera frame to COLMAP's: flip y and z.
const Eigen::Matrix3d kFlipYZ = Eigen::Vector3d(1, -1, -1).asDiagonal();

std::string FormatNumber(double value) {
  std::ostringstream stream;
  stream.precision(17);
  stream << value;
  return stream.str();
}

// Reads whitespace-separated numbers line by line, for error messages with
// line numbers.
class NumberReader {
 public:
  explicit NumberReader(const std::string& path)
      : path_(path), text_(ReadTextFile(path)), in_(text_) {}

  // The next non-comment line split into fields.
  std::vector<std::string> Line(const char* what) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_number_;
      line = StringTrim(line);
      if (line.empty() || line[0] == '#') continue;
      std::vector<std::string> fields;
      std::istringstream stream(line);
      std::string field;
      while (stream >> field) fields.push_back(field);
      return fields;
    }
    ThrowError(path_, ": unexpected end of file reading ", what);
  }

  std::vector<double> Numbers(size_t count, const char* what) {
    const std::vector<std::string> fields = Line(what);
    if (fields.size() != count) {
      ThrowError(path_,
                 ":",
                 line_number_,
                 ": expected ",
                 count,
                 " numbers for ",
                 what,
                 ", got ",
                 fields.size());
    }
    return Parse(fields, what);
  }

  std::vector<double> Parse(const std::vector<std::string>& fields,
                            const char* what) {
    std::vector<double> values;
    for (const std::string& field : fields) {
      char* end = nullptr;
      const double value = std::strtod(field.c_str(), &end);
      // The whole field, so that an embedded NUL cannot end it early.
      if (end == field.c_str() || end != field.c_str() + field.size()) {
        ThrowError(
            path_, ":", line_number_, ": bad number \"", field, "\" in ", what);
      }
      values.push_back(value);
    }
    return values;
  }

  // A count or index stored as a number: an integer in [0, max_value], checked
  // before any conversion (casting a huge or NaN double is undefined).
  int Integer(double value, double max_value, const std::string& what) const {
    if (!(value >= 0 && value <= max_value) || value != std::floor(value)) {
      Fail(what + " " + FormatNumber(value) + " is not an integer in [0, " +
           FormatNumber(max_value) + "]");
    }
    return static_cast<int>(value);
  }

  [[noreturn]] void Fail(const std::string& what) const {
    ThrowError(path_, ":", line_number_, ": ", what);
  }

 private:
  std::string path_;
  std::string text_;
  std::istringstream in_;
  size_t line_number_ = 0;
};

}  // namespace

BundlerFile ReadBundlerFile(const std::string& path) {
  // The header comment "# Bundle file v0.3" is skipped with other comments;
  // v0.3 is the only version 1DSfM uses.
  NumberReader reader(path);
  const std::vector<double> counts = reader.Numbers(2, "the counts");
  const double kMaxCount = std::numeric_limits<int>::max();
  const int num_cameras = reader.Integer(counts[0], kMaxCount, "camera count");
  const int num_points = reader.Integer(counts[1], kMaxCount, "point count");
  BundlerFile bundle;
  // Grown while parsing, so a corrupt count fails at the end of the file
  // instead of allocating for it up front.
  for (int i = 0; i < num_cameras; ++i) {
    BundlerCamera& camera = bundle.cameras.emplace_back();
    const auto intrinsics = reader.Numbers(3, "camera f k1 k2");
    camera.focal_length = intrinsics[0];
    camera.k1 = intrinsics[1];
    camera.k2 = intrinsics[2];
    for (int row = 0; row < 3; ++row) {
      const auto values = reader.Numbers(3, "a camera rotation row");
      camera.rotation.row(row) << values[0], values[1], values[2];
    }
    const auto t = reader.Numbers(3, "a camera translation");
    camera.translation << t[0], t[1], t[2];
  }
  for (int i = 0; i < num_points; ++i) {
    BundlerPoint& point = bundle.points.emplace_back();
    const auto xyz = reader.Numbers(3, "a point position");
    point.xyz << xyz[0], xyz[1], xyz[2];
    const auto color = reader.Numbers(3, "a point colour");
    for (int k = 0; k < 3; ++k) {
      point.color(k) = reader.Integer(color[k], 255, "colour");
    }
    const auto fields = reader.Line("a point view list");
    const auto values = reader.Parse(fields, "a point view list");
    if (values.empty() || reader.Integer(values[0], kMaxCount, "view count") !=
                              static_cast<double>(values.size() - 1) / 4) {
      reader.Fail("view list length does not match its count");
    }
    const size_t num_views = (values.size() - 1) / 4;
    for (size_t v = 0; v < num_views; ++v) {
      BundlerView view;
      if (num_cameras == 0) reader.Fail("view of a camera, but no cameras");
      view.camera_idx = reader.Integer(
          values[1 + 4 * v], num_cameras - 1, "view camera index");
      view.key_idx =
          reader.Integer(values[2 + 4 * v], kMaxCount, "view key index");
      view.x = values[3 + 4 * v];
      view.y = values[4 + 4 * v];
      point.views.push_back(view);
    }
  }
  return bundle;
}

Reconstruction BundlerToReconstruction(
    const BundlerFile& bundle,
    const std::vector<std::string>& image_names,
    const std::vector<std::pair<int, int>>& image_sizes) {
  if (image_names.size() != bundle.cameras.size() ||
      image_sizes.size() != bundle.cameras.size()) {
    ThrowError("Bundler file has ",
               bundle.cameras.size(),
               " cameras but the image list has ",
               image_names.size(),
               " images");
  }
  Reconstruction reconstruction;
  const int radial = CameraModelNameToId("RADIAL");
  for (size_t i = 0; i < bundle.cameras.size(); ++i) {
    const BundlerCamera& bundler_camera = bundle.cameras[i];
    if (!bundler_camera.IsRegistered()) continue;
    const image_t id = static_cast<image_t>(i + 1);
    ModelCamera camera;
    camera.camera_id = id;
    camera.model_id = radial;
    camera.width = image_sizes[i].first;
    camera.height = image_sizes[i].second;
    camera.params = {bundler_camera.focal_length,
                     0.5 * camera.width,
                     0.5 * camera.height,
                     bundler_camera.k1,
                     bundler_camera.k2};
    reconstruction.cameras[id] = camera;
    ModelImage image;
    image.image_id = id;
    image.camera_id = id;
    image.name = image_names[i];
    const Eigen::Matrix3d rotation = kFlipYZ * bundler_camera.rotation;
    const Eigen::Quaterniond quaternion(rotation);
    image.qvec << quaternion.w(), quaternion.x(), quaternion.y(),
        quaternion.z();
    image.tvec = kFlipYZ * bundler_camera.translation;
    reconstruction.images[id] = image;
  }
  point3D_t point3D_id = 1;
  for (const BundlerPoint& bundler_point : bundle.points) {
    ModelPoint3D point;
    point.xyz = bundler_point.xyz;
    point.color = bundler_point.color.cwiseMax(0).cwiseMin(255).cast<uint8_t>();
    for (const BundlerView& view : bundler_point.views) {
      const image_t id = static_cast<image_t>(view.camera_idx + 1);
      auto image = reconstruction.images.find(id);
      if (image == reconstruction.images.end()) continue;
      const ModelCamera& camera = reconstruction.cameras.at(id);
      TrackElement element;
      element.image_id = id;
      element.point2D_idx =
          static_cast<point2D_t>(image->second.points2D.size());
      image->second.points2D.emplace_back(camera.params[1] + view.x,
                                          camera.params[2] - view.y);
      image->second.point3D_ids.push_back(point3D_id);
      point.track.push_back(element);
    }
    if (!point.track.empty()) {
      reconstruction.points3D[point3D_id++] = point;
    }
  }
  return reconstruction;
}

BundlerFile ReconstructionToBundler(
    const Reconstruction& reconstruction,
    const std::vector<std::string>& image_names) {
  BundlerFile bundle;
  bundle.cameras.resize(image_names.size());
  std::map<image_t, int> camera_index;
  for (size_t i = 0; i < image_names.size(); ++i) {
    const image_t image_id = reconstruction.FindImageWithName(image_names[i]);
    if (image_id == kInvalidImageId) continue;
    const ModelImage& image = reconstruction.images.at(image_id);
    const ModelCamera& camera = reconstruction.cameras.at(image.camera_id);
    const std::string model = CameraModelIdToName(camera.model_id);
    BundlerCamera& bundler_camera = bundle.cameras[i];
    bundler_camera.focal_length = camera.params.at(0);
    if (model == "SIMPLE_RADIAL") {
      bundler_camera.k1 = camera.params.at(3);
    } else if (model == "RADIAL") {
      bundler_camera.k1 = camera.params.at(3);
      bundler_camera.k2 = camera.params.at(4);
    } else if (model != "SIMPLE_PINHOLE" && model != "PINHOLE") {
      ThrowError("cannot write camera model ", model, " as Bundler");
    }
    bundler_camera.rotation = kFlipYZ * image.RotationMatrix();
    bundler_camera.translation = kFlipYZ * image.tvec;
    camera_index[image_id] = static_cast<int>(i);
  }
  for (const auto& [point3D_id, point3D] : reconstruction.points3D) {
    BundlerPoint point;
    point.xyz = point3D.xyz;
    point.color = point3D.color.cast<int>();
    for (const TrackElement& element : point3D.track) {
      const auto index = camera_index.find(element.image_id);
      if (index == camera_index.end()) continue;
      const ModelImage& image = reconstruction.images.at(element.image_id);
      const ModelCamera& camera = reconstruction.cameras.at(image.camera_id);
      const double cx = 0.5 * camera.width;
      const double cy = 0.5 * camera.height;
      BundlerView view;
      view.camera_idx = index->second;
      view.key_idx = static_cast<int>(element.point2D_idx);
      if (element.point2D_idx < image.points2D.size()) {
        view.x = image.points2D[element.point2D_idx].x() - cx;
        view.y = cy - image.points2D[element.point2D_idx].y();
      }
      point.views.push_back(view);
    }
    if (!point.views.empty()) bundle.points.push_back(point);
  }
  return bundle;
}

std::vector<std::string> ReadBundlerImageList(const std::string& path) {
  std::vector<std::string> names;
  std::istringstream in(ReadTextFile(path));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string name;
    if (fields >> name) names.push_back(name);
  }
  return names;
}

}  // namespace colmap_gcn
