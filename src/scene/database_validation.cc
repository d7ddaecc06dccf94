#include "scene/database_validation.h"

#include <sqlite3.h>

#include <map>
#include <string>

#include "scene/camera_models.h"
#include "scene/sqlite_statement.h"
#include "util/error.h"

namespace colmap_gcn {
namespace {

// More rows than any image has features; keeps rows * cols * size in range.
const int64_t kMaxFeatureRows = int64_t{1} << 40;

// One image's keypoints or descriptors row: (present, rows, cols, bytes).
struct FeatureShape {
  bool present = false;
  int64_t rows = 0;
  int64_t cols = 0;
  int64_t num_bytes = 0;
};

FeatureShape ReadShape(const SqliteStatement& stmt, const int col) {
  FeatureShape shape;
  shape.present = stmt.Int64(col) != 0;
  shape.rows = stmt.Int64(col + 1);
  shape.cols = stmt.Int64(col + 2);
  // length() of a NULL blob is NULL: COLMAP reads it as empty.
  shape.num_bytes = stmt.IsNull(col + 3) ? 0 : stmt.Int64(col + 3);
  return shape;
}

// What COLMAP 3.8 aborts on in one keypoints or descriptors row ("" when
// it reads it): keypoints are float32 with 2, 4 or 6 columns, descriptors
// uint8 with 128 (SIFT); the blob holds exactly rows x cols values.
std::string ShapeProblem(const char* what, const FeatureShape& shape) {
  if (!shape.present) return "";
  const bool keypoints = std::string(what) == "keypoints";
  const int64_t element_size = keypoints ? 4 : 1;
  if (shape.rows < 0 || shape.rows > kMaxFeatureRows) {
    return std::string("has ") + what + " with " + std::to_string(shape.rows) +
           " rows";
  }
  if (keypoints && shape.cols != 2 && shape.cols != 4 && shape.cols != 6) {
    return "has keypoints with " + std::to_string(shape.cols) +
           " columns; COLMAP reads 2, 4 or 6";
  }
  if (!keypoints && shape.cols != 128) {
    return "has descriptors with " + std::to_string(shape.cols) +
           " columns; COLMAP 3.8 reads 128 (SIFT)";
  }
  const int64_t expected = shape.rows * shape.cols * element_size;
  if (shape.num_bytes != expected) {
    return std::string("has a ") + what + " blob of " +
           std::to_string(shape.num_bytes) + " bytes, not the " +
           std::to_string(expected) + " its shape " +
           std::to_string(shape.rows) + "x" + std::to_string(shape.cols) +
           " needs";
  }
  return "";
}

std::string KnownModelIds() {
  int num_models = 0;
  while (!CameraModelIdToName(num_models).empty()) ++num_models;
  return "0-" + std::to_string(num_models - 1);
}

struct CameraRow {
  int64_t model = 0;
  int64_t num_param_bytes = 0;
};

// What COLMAP 3.8 aborts on in a camera row, as a predicate ("has ..."),
// "" for nothing: a model id it does not know, or a params blob that does
// not hold the model's parameter count of doubles.
std::string CameraProblem(const CameraRow& camera) {
  const bool known =
      camera.model == static_cast<int>(camera.model) &&
      !CameraModelIdToName(static_cast<int>(camera.model)).empty();
  if (!known) {
    return "has model id " + std::to_string(camera.model) +
           ", unknown to COLMAP 3.8 (ids " + KnownModelIds() + ")";
  }
  const int model = static_cast<int>(camera.model);
  const int64_t num_params = CameraModelNumParams(model);
  if (camera.num_param_bytes != num_params * 8) {
    return "has " + std::to_string(camera.num_param_bytes) +
           " bytes of parameters, not the " + std::to_string(num_params) +
           " doubles of model " + CameraModelIdToName(model);
  }
  return "";
}

// What COLMAP 3.8 aborts on in one image's rows, "" for nothing.
std::string ImageProblem(const std::map<camera_t, CameraRow>& cameras,
                         const camera_t camera_id,
                         const FeatureShape& keypoints,
                         const FeatureShape& descriptors) {
  const auto camera = cameras.find(camera_id);
  if (camera == cameras.end()) {
    return "refers to camera " + std::to_string(camera_id) +
           ", which is not in the cameras table";
  }
  const std::string camera_problem = CameraProblem(camera->second);
  if (!camera_problem.empty()) {
    return "uses camera " + std::to_string(camera_id) + ", which " +
           camera_problem;
  }
  std::string problem = ShapeProblem("keypoints", keypoints);
  if (problem.empty()) problem = ShapeProblem("descriptors", descriptors);
  if (problem.empty() && keypoints.present && descriptors.present &&
      keypoints.rows != descriptors.rows) {
    problem = "has " + std::to_string(keypoints.rows) + " keypoints but " +
              std::to_string(descriptors.rows) + " descriptors";
  }
  return problem;
}

}  // namespace

void ValidateDatabaseForColmap(const Database& database) {
  const std::string& path = database.Path();
  sqlite3* db = database.Handle();
  std::map<camera_t, CameraRow> cameras;
  {
    SqliteStatement stmt(
        db, path, "SELECT camera_id, model, length(params) FROM cameras");
    while (stmt.Step()) {
      CameraRow& camera = cameras[static_cast<camera_t>(stmt.Int64(0))];
      camera.model = stmt.Int64(1);
      camera.num_param_bytes = stmt.IsNull(2) ? 0 : stmt.Int64(2);
    }
  }
  // Only the small columns and the blob lengths, which SQLite reads from the
  // record header without loading the blobs.
  SqliteStatement stmt(
      db,
      path,
      "SELECT i.image_id, i.name, i.camera_id,"
      " k.image_id IS NOT NULL, k.rows, k.cols, length(k.data),"
      " d.image_id IS NOT NULL, d.rows, d.cols, length(d.data)"
      " FROM images AS i"
      " LEFT JOIN keypoints AS k ON k.image_id = i.image_id"
      " LEFT JOIN descriptors AS d ON d.image_id = i.image_id"
      " ORDER BY i.image_id");
  std::string first_problem;
  size_t num_bad_images = 0;
  while (stmt.Step()) {
    const camera_t camera_id = static_cast<camera_t>(stmt.Int64(2));
    const FeatureShape keypoints = ReadShape(stmt, 3);
    const FeatureShape descriptors = ReadShape(stmt, 7);
    const std::string problem =
        ImageProblem(cameras, camera_id, keypoints, descriptors);
    if (problem.empty()) continue;
    if (num_bad_images++ == 0) {
      first_problem = "image \"" + stmt.Text(1) + "\" (id " +
                      std::to_string(stmt.Int64(0)) + ") " + problem;
    }
  }
  if (num_bad_images > 0) {
    ThrowError("database ",
               path,
               ": ",
               first_problem,
               num_bad_images > 1
                   ? " (and " + std::to_string(num_bad_images - 1) +
                         " more images with such problems)"
                   : "",
               "; COLMAP would abort on it");
  }
  // COLMAP reads every camera, used or not.
  for (const auto& [camera_id, camera] : cameras) {
    const std::string problem = CameraProblem(camera);
    if (!problem.empty()) {
      ThrowError("database ",
                 path,
                 ": camera ",
                 camera_id,
                 " ",
                 problem,
                 "; COLMAP would abort on it");
    }
  }
}

}  // namespace colmap_gcn
