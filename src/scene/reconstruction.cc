#include "scene/reconstruction.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <limits>
#include <sstream>
#include <type_traits>

#include "scene/camera_models.h"
#include "util/binary_io.h"
#include "util/error.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

////////////////////////////////////////////////////////////////////////////////
// Binary format helpers. COLMAP writes little-endian PODs without padding; we
// only target little-endian hosts, so bytes are copied as they are.
////////////////////////////////////////////////////////////////////////////////

// A ByteReader over a whole COLMAP binary model file.
class BinaryReader {
 public:
  explicit BinaryReader(const std::string& path)
      : path_(path),
        data_(ReadRequiredFile(path)),
        reader_(data_, 0, data_.size(), [this](size_t position) {
          ThrowError("truncated COLMAP model file ",
                     path_,
                     " (unexpected end at byte ",
                     position,
                     " of ",
                     data_.size(),
                     ")");
        }) {}
  BinaryReader(const BinaryReader&) = delete;
  BinaryReader& operator=(const BinaryReader&) = delete;

  template <typename T>
  T Read() {
    return reader_.Get<T>();
  }

  // A NUL-terminated string, as COLMAP stores image names.
  std::string ReadString() { return reader_.GetCString(); }

  // Caps a count read from the file by what the remaining bytes can hold, so
  // a corrupt count fails as truncation instead of a huge allocation.
  size_t ReadCount(const size_t min_element_bytes) {
    const uint64_t count = Read<uint64_t>();
    if (count > reader_.Remaining() / min_element_bytes) {
      reader_.Fail();
    }
    return static_cast<size_t>(count);
  }

  void ExpectEnd() const {
    if (reader_.Remaining() != 0) {
      ThrowError("malformed COLMAP model file ",
                 path_,
                 ": ",
                 reader_.Remaining(),
                 " unexpected trailing bytes");
    }
  }

  [[noreturn]] void Fail(const std::string& what) const {
    ThrowError("malformed COLMAP model file ", path_, ": ", what);
  }

 private:
  static std::string ReadRequiredFile(const std::string& path) {
    if (!ExistsFile(path)) {
      ThrowError("COLMAP model file not found: ", path);
    }
    return ReadTextFile(path);
  }

  std::string path_;
  std::string data_;
  ByteReader reader_;
};

////////////////////////////////////////////////////////////////////////////////
// Text format helpers.
////////////////////////////////////////////////////////////////////////////////

// Iterates over the lines of a text model file and parses their
// whitespace-separated fields, reporting errors with file and line number.
class TextReader {
 public:
  explicit TextReader(const std::string& path) : path_(path) {
    if (!ExistsFile(path)) {
      ThrowError("COLMAP model file not found: ", path);
    }
    stream_.str(ReadTextFile(path));
  }

  // Next line that is neither empty nor a '#' comment; false at the end.
  bool NextDataLine(std::string* line) {
    while (NextLine(line)) {
      if (!line->empty() && (*line)[0] != '#') {
        return true;
      }
    }
    return false;
  }

  // Next line, which may be empty (the points line of images.txt). Missing
  // at the end of the file counts as empty.
  bool NextLine(std::string* line) {
    if (!std::getline(stream_, *line)) {
      line->clear();
      return false;
    }
    ++line_number_;
    *line = StringTrim(*line);
    return true;
  }

  static std::vector<std::string> Fields(const std::string& line) {
    std::vector<std::string> fields;
    std::istringstream stream(line);
    std::string field;
    while (stream >> field) {
      fields.push_back(field);
    }
    return fields;
  }

  double ParseDouble(const std::string& field) const {
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(field.c_str(), &end);
    // The whole field, so that an embedded NUL cannot end it early.
    if (field.empty() || end != field.c_str() + field.size() ||
        errno == ERANGE) {
      Fail("invalid number '" + field + "'");
    }
    return value;
  }

  int64_t ParseInt(const std::string& field,
                   const int64_t min_value,
                   const int64_t max_value) const {
    errno = 0;
    char* end = nullptr;
    const long long value = std::strtoll(field.c_str(), &end, 10);
    if (field.empty() || end != field.c_str() + field.size() ||
        errno == ERANGE || value < min_value || value > max_value) {
      Fail("invalid integer '" + field + "'");
    }
    return value;
  }

  [[noreturn]] void Fail(const std::string& what) const {
    ThrowError(
        "malformed COLMAP model file ", path_, ":", line_number_, ": ", what);
  }

 private:
  std::string path_;
  std::istringstream stream_;
  size_t line_number_ = 0;
};

constexpr int64_t kMaxUint32 = std::numeric_limits<uint32_t>::max();
constexpr int64_t kMaxInt64 = std::numeric_limits<int64_t>::max();

// Full double precision so that text round trips are exact.
void SetFullPrecision(std::ostringstream* stream) {
  stream->precision(std::numeric_limits<double>::max_digits10);
}

int CheckedNumParams(const ModelCamera& camera, const std::string& path) {
  const int num_params = CameraModelNumParams(camera.model_id);
  if (num_params < 0) {
    ThrowError("cannot write ",
               path,
               ": camera ",
               camera.camera_id,
               " has unknown model id ",
               camera.model_id);
  }
  if (camera.params.size() != static_cast<size_t>(num_params)) {
    ThrowError("cannot write ",
               path,
               ": camera ",
               camera.camera_id,
               " has ",
               camera.params.size(),
               " params, model ",
               CameraModelIdToName(camera.model_id),
               " needs ",
               num_params);
  }
  return num_params;
}

void CheckImageArrays(const ModelImage& image, const std::string& path) {
  if (image.points2D.size() != image.point3D_ids.size()) {
    ThrowError("cannot write ",
               path,
               ": image ",
               image.image_id,
               " has ",
               image.points2D.size(),
               " points2D but ",
               image.point3D_ids.size(),
               " point3D ids");
  }
}

////////////////////////////////////////////////////////////////////////////////
// Readers.
////////////////////////////////////////////////////////////////////////////////

void ReadCamerasBinary(const std::string& path,
                       std::map<camera_t, ModelCamera>* cameras) {
  BinaryReader reader(path);
  const size_t num_cameras = reader.ReadCount(24);
  for (size_t i = 0; i < num_cameras; ++i) {
    ModelCamera camera;
    camera.camera_id = reader.Read<uint32_t>();
    camera.model_id = reader.Read<int32_t>();
    camera.width = reader.Read<uint64_t>();
    camera.height = reader.Read<uint64_t>();
    // The parameter count is implied by the model, so an unknown model makes
    // the rest of the file unreadable.
    const int num_params = CameraModelNumParams(camera.model_id);
    if (num_params < 0) {
      reader.Fail("camera " + std::to_string(camera.camera_id) +
                  " has unknown model id " + std::to_string(camera.model_id));
    }
    camera.params.resize(num_params);
    for (double& param : camera.params) {
      param = reader.Read<double>();
    }
    (*cameras)[camera.camera_id] = std::move(camera);
  }
  reader.ExpectEnd();
}

void ReadImagesBinary(const std::string& path,
                      std::map<image_t, ModelImage>* images) {
  BinaryReader reader(path);
  const size_t num_images = reader.ReadCount(73);
  for (size_t i = 0; i < num_images; ++i) {
    ModelImage image;
    image.image_id = reader.Read<uint32_t>();
    for (int k = 0; k < 4; ++k) image.qvec(k) = reader.Read<double>();
    for (int k = 0; k < 3; ++k) image.tvec(k) = reader.Read<double>();
    image.camera_id = reader.Read<uint32_t>();
    image.name = reader.ReadString();
    const size_t num_points2D = reader.ReadCount(24);
    image.points2D.resize(num_points2D);
    image.point3D_ids.resize(num_points2D);
    for (size_t j = 0; j < num_points2D; ++j) {
      image.points2D[j].x() = reader.Read<double>();
      image.points2D[j].y() = reader.Read<double>();
      // -1 as uint64 is kInvalidPoint3DId.
      image.point3D_ids[j] = reader.Read<uint64_t>();
    }
    (*images)[image.image_id] = std::move(image);
  }
  reader.ExpectEnd();
}

void ReadPoints3DBinary(const std::string& path,
                        std::map<point3D_t, ModelPoint3D>* points3D) {
  BinaryReader reader(path);
  const size_t num_points = reader.ReadCount(51);
  for (size_t i = 0; i < num_points; ++i) {
    const point3D_t point3D_id = reader.Read<uint64_t>();
    ModelPoint3D point;
    for (int k = 0; k < 3; ++k) point.xyz(k) = reader.Read<double>();
    for (int k = 0; k < 3; ++k) point.color(k) = reader.Read<uint8_t>();
    point.error = reader.Read<double>();
    const size_t track_length = reader.ReadCount(8);
    point.track.resize(track_length);
    for (TrackElement& element : point.track) {
      element.image_id = reader.Read<uint32_t>();
      element.point2D_idx = reader.Read<uint32_t>();
    }
    (*points3D)[point3D_id] = std::move(point);
  }
  reader.ExpectEnd();
}

void ReadCamerasText(const std::string& path,
                     std::map<camera_t, ModelCamera>* cameras) {
  TextReader reader(path);
  std::string line;
  while (reader.NextDataLine(&line)) {
    const std::vector<std::string> fields = TextReader::Fields(line);
    if (fields.size() < 4) {
      reader.Fail("expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS[]");
    }
    ModelCamera camera;
    camera.camera_id =
        static_cast<camera_t>(reader.ParseInt(fields[0], 0, kMaxUint32));
    camera.model_id = CameraModelNameToId(fields[1]);
    if (camera.model_id < 0) {
      reader.Fail("unknown camera model '" + fields[1] + "'");
    }
    camera.width =
        static_cast<uint64_t>(reader.ParseInt(fields[2], 0, kMaxInt64));
    camera.height =
        static_cast<uint64_t>(reader.ParseInt(fields[3], 0, kMaxInt64));
    for (size_t i = 4; i < fields.size(); ++i) {
      camera.params.push_back(reader.ParseDouble(fields[i]));
    }
    const int num_params = CameraModelNumParams(camera.model_id);
    if (camera.params.size() != static_cast<size_t>(num_params)) {
      reader.Fail("model " + fields[1] + " needs " +
                  std::to_string(num_params) + " params, got " +
                  std::to_string(camera.params.size()));
    }
    if (cameras->count(camera.camera_id) > 0) {
      reader.Fail("duplicate camera id " + fields[0]);
    }
    (*cameras)[camera.camera_id] = std::move(camera);
  }
}

// Parses the second line of an image: X Y POINT3D_ID triples.
void ParsePoints2DLine(const TextReader& reader,
                       const std::string& line,
                       ModelImage* image) {
  const std::vector<std::string> fields = TextReader::Fields(line);
  if (fields.size() % 3 != 0) {
    reader.Fail("expected (X, Y, POINT3D_ID) triples for image " +
                std::to_string(image->image_id));
  }
  for (size_t i = 0; i < fields.size(); i += 3) {
    image->points2D.emplace_back(reader.ParseDouble(fields[i]),
                                 reader.ParseDouble(fields[i + 1]));
    const int64_t point3D_id = reader.ParseInt(fields[i + 2], -1, kMaxInt64);
    image->point3D_ids.push_back(point3D_id < 0
                                     ? kInvalidPoint3DId
                                     : static_cast<point3D_t>(point3D_id));
  }
}

void ReadImagesText(const std::string& path,
                    std::map<image_t, ModelImage>* images) {
  TextReader reader(path);
  std::string line;
  while (reader.NextDataLine(&line)) {
    const std::vector<std::string> fields = TextReader::Fields(line);
    if (fields.size() < 10) {
      reader.Fail("expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME");
    }
    ModelImage image;
    image.image_id =
        static_cast<image_t>(reader.ParseInt(fields[0], 0, kMaxUint32));
    for (int k = 0; k < 4; ++k)
      image.qvec(k) = reader.ParseDouble(fields[1 + k]);
    for (int k = 0; k < 3; ++k)
      image.tvec(k) = reader.ParseDouble(fields[5 + k]);
    image.camera_id =
        static_cast<camera_t>(reader.ParseInt(fields[8], 0, kMaxUint32));
    // The name is the rest of the line (COLMAP itself stops at the first
    // space; taking the rest is a superset).
    // Fields() splits on all of isspace's characters, so skipping the nine
    // fields with the same set always lands inside the line.
    const char* kSpace = " \t\n\v\f\r";
    size_t name_begin = 0;
    for (int k = 0; k < 9; ++k) {
      name_begin = line.find_first_not_of(kSpace, name_begin);
      name_begin = line.find_first_of(kSpace, name_begin);
    }
    image.name = StringTrim(line.substr(name_begin));
    if (images->count(image.image_id) > 0) {
      reader.Fail("duplicate image id " + fields[0]);
    }
    // The points line always follows, possibly empty; it is not skipped like
    // a comment so that an empty line keeps the two-line structure.
    reader.NextLine(&line);
    ParsePoints2DLine(reader, line, &image);
    (*images)[image.image_id] = std::move(image);
  }
}

void ReadPoints3DText(const std::string& path,
                      std::map<point3D_t, ModelPoint3D>* points3D) {
  TextReader reader(path);
  std::string line;
  while (reader.NextDataLine(&line)) {
    const std::vector<std::string> fields = TextReader::Fields(line);
    if (fields.size() < 8 || (fields.size() - 8) % 2 != 0) {
      reader.Fail(
          "expected POINT3D_ID X Y Z R G B ERROR then (IMAGE_ID, "
          "POINT2D_IDX) pairs");
    }
    const point3D_t point3D_id =
        static_cast<point3D_t>(reader.ParseInt(fields[0], 0, kMaxInt64));
    ModelPoint3D point;
    for (int k = 0; k < 3; ++k)
      point.xyz(k) = reader.ParseDouble(fields[1 + k]);
    for (int k = 0; k < 3; ++k) {
      point.color(k) =
          static_cast<uint8_t>(reader.ParseInt(fields[4 + k], 0, 255));
    }
    point.error = reader.ParseDouble(fields[7]);
    for (size_t i = 8; i < fields.size(); i += 2) {
      TrackElement element;
      element.image_id =
          static_cast<image_t>(reader.ParseInt(fields[i], 0, kMaxUint32));
      element.point2D_idx =
          static_cast<point2D_t>(reader.ParseInt(fields[i + 1], 0, kMaxUint32));
      point.track.push_back(element);
    }
    if (points3D->count(point3D_id) > 0) {
      reader.Fail("duplicate point3D id " + fields[0]);
    }
    (*points3D)[point3D_id] = std::move(point);
  }
}

}  // namespace

Eigen::Matrix3d ModelImage::RotationMatrix() const {
  return Eigen::Quaterniond(qvec(0), qvec(1), qvec(2), qvec(3))
      .normalized()
      .toRotationMatrix();
}

Eigen::Vector3d ModelImage::ProjectionCenter() const {
  return -RotationMatrix().transpose() * tvec;
}

size_t ModelImage::NumPoints3D() const {
  size_t num_points3D = 0;
  for (const point3D_t point3D_id : point3D_ids) {
    num_points3D += point3D_id != kInvalidPoint3DId ? 1 : 0;
  }
  return num_points3D;
}

void Reconstruction::Read(const std::string& path) {
  const bool has_binary = ExistsFile(JoinPaths(path, "cameras.bin")) &&
                          ExistsFile(JoinPaths(path, "images.bin")) &&
                          ExistsFile(JoinPaths(path, "points3D.bin"));
  if (has_binary) {
    ReadBinary(path);
  } else if (ExistsFile(JoinPaths(path, "cameras.txt")) &&
             ExistsFile(JoinPaths(path, "images.txt"))) {
    ReadText(path);
  } else {
    ThrowError("no COLMAP model (cameras/images/points3D .bin or .txt) in ",
               path);
  }
}

void Reconstruction::ReadText(const std::string& path) {
  // Parse into a fresh model so that a failure leaves *this untouched.
  Reconstruction model;
  ReadCamerasText(JoinPaths(path, "cameras.txt"), &model.cameras);
  ReadImagesText(JoinPaths(path, "images.txt"), &model.images);
  const std::string points3D_path = JoinPaths(path, "points3D.txt");
  if (ExistsFile(points3D_path)) {
    ReadPoints3DText(points3D_path, &model.points3D);
  }
  *this = std::move(model);
}

void Reconstruction::ReadBinary(const std::string& path) {
  Reconstruction model;
  ReadCamerasBinary(JoinPaths(path, "cameras.bin"), &model.cameras);
  ReadImagesBinary(JoinPaths(path, "images.bin"), &model.images);
  ReadPoints3DBinary(JoinPaths(path, "points3D.bin"), &model.points3D);
  *this = std::move(model);
}

void Reconstruction::WriteText(const std::string& path) const {
  CreateDirIfNotExists(path);

  const std::string cameras_path = JoinPaths(path, "cameras.txt");
  std::ostringstream cameras_text;
  SetFullPrecision(&cameras_text);
  cameras_text << "# Camera list with one line of data per camera:\n"
               << "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
               << "# Number of cameras: " << cameras.size() << "\n";
  for (const auto& [camera_id, camera] : cameras) {
    CheckedNumParams(camera, cameras_path);
    cameras_text << camera_id << " " << CameraModelIdToName(camera.model_id)
                 << " " << camera.width << " " << camera.height;
    for (const double param : camera.params) {
      cameras_text << " " << param;
    }
    cameras_text << "\n";
  }

  const std::string images_path = JoinPaths(path, "images.txt");
  size_t num_observations = 0;
  for (const auto& [image_id, image] : images) {
    num_observations += image.NumPoints3D();
  }
  std::ostringstream images_text;
  SetFullPrecision(&images_text);
  images_text << "# Image list with two lines of data per image:\n"
              << "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
              << "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
              << "# Number of images: " << images.size()
              << ", mean observations per image: "
              << (images.empty()
                      ? 0.0
                      : static_cast<double>(num_observations) / images.size())
              << "\n";
  for (const auto& [image_id, image] : images) {
    CheckImageArrays(image, images_path);
    images_text << image_id;
    for (int k = 0; k < 4; ++k) images_text << " " << image.qvec(k);
    for (int k = 0; k < 3; ++k) images_text << " " << image.tvec(k);
    images_text << " " << image.camera_id << " " << image.name << "\n";
    for (size_t j = 0; j < image.points2D.size(); ++j) {
      images_text << (j > 0 ? " " : "") << image.points2D[j].x() << " "
                  << image.points2D[j].y() << " ";
      if (image.point3D_ids[j] == kInvalidPoint3DId) {
        images_text << -1;
      } else {
        images_text << image.point3D_ids[j];
      }
    }
    images_text << "\n";
  }

  size_t track_length_sum = 0;
  for (const auto& [point3D_id, point] : points3D) {
    track_length_sum += point.track.size();
  }
  std::ostringstream points_text;
  SetFullPrecision(&points_text);
  points_text << "# 3D point list with one line of data per point:\n"
              << "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as "
                 "(IMAGE_ID, POINT2D_IDX)\n"
              << "# Number of points: " << points3D.size()
              << ", mean track length: "
              << (points3D.empty()
                      ? 0.0
                      : static_cast<double>(track_length_sum) / points3D.size())
              << "\n";
  for (const auto& [point3D_id, point] : points3D) {
    points_text << point3D_id << " " << point.xyz(0) << " " << point.xyz(1)
                << " " << point.xyz(2) << " "
                << static_cast<int>(point.color(0)) << " "
                << static_cast<int>(point.color(1)) << " "
                << static_cast<int>(point.color(2)) << " " << point.error;
    for (const TrackElement& element : point.track) {
      points_text << " " << element.image_id << " " << element.point2D_idx;
    }
    points_text << "\n";
  }

  WriteFileAtomically(cameras_path, cameras_text.str());
  WriteFileAtomically(images_path, images_text.str());
  WriteFileAtomically(JoinPaths(path, "points3D.txt"), points_text.str());
}

image_t Reconstruction::FindImageWithName(const std::string& name) const {
  for (const auto& [image_id, image] : images) {
    if (image.name == name) {
      return image_id;
    }
  }
  return kInvalidImageId;
}

}  // namespace colmap_gcn
