#include "evaluation/ground_truth.h"

#include <cmath>
#include <filesystem>
#include <map>

#include "scene/database.h"
#include "scene/database_copy.h"
#include "scene/reconstruction_stats.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

bool SameIntrinsics(const ModelCamera& a, const ModelCamera& b) {
  if (a.model_id != b.model_id || a.width != b.width || a.height != b.height ||
      a.params.size() != b.params.size()) {
    return false;
  }
  for (size_t i = 0; i < a.params.size(); ++i) {
    if (std::abs(a.params[i] - b.params[i]) >
        1e-6 * std::max(1.0, std::abs(a.params[i]))) {
      return false;
    }
  }
  return true;
}

}  // namespace

Reconstruction TriangulateOnGroundTruth(const ColmapRunner& colmap,
                                        const Reconstruction& ground_truth,
                                        const std::string& database_path,
                                        const std::string& work_dir) {
  namespace fs = std::filesystem;
  CreateDirIfNotExists(work_dir);
  const std::string work_db = JoinPaths(work_dir, "database.db");
  const std::string input_path = JoinPaths(work_dir, "gt_input");
  const std::string output_path = JoinPaths(work_dir, "triangulated");
  std::error_code ec;
  fs::remove_all(output_path, ec);
  CopyDatabase(database_path, work_db);

  Reconstruction input;
  {
    Database database(work_db, Database::Mode::kReadWrite);
    std::map<camera_t, const ModelCamera*> assigned;
    for (const DatabaseImage& db_image : database.ReadAllImages()) {
      const image_t gt_id = ground_truth.FindImageWithName(db_image.name);
      if (gt_id == kInvalidImageId) continue;
      const ModelImage& gt_image = ground_truth.images.at(gt_id);
      const ModelCamera& gt_camera =
          ground_truth.cameras.at(gt_image.camera_id);
      auto it = assigned.find(db_image.camera_id);
      if (it != assigned.end()) {
        if (!SameIntrinsics(*it->second, gt_camera)) {
          ThrowError("database camera ",
                     db_image.camera_id,
                     " is shared by images with different ground-truth "
                     "intrinsics; extract with one camera per image");
        }
      } else {
        assigned[db_image.camera_id] = &gt_camera;
        DatabaseCamera camera;
        camera.camera_id = db_image.camera_id;
        camera.model_id = gt_camera.model_id;
        camera.width = gt_camera.width;
        camera.height = gt_camera.height;
        camera.params = gt_camera.params;
        camera.has_prior_focal_length = true;
        database.UpdateCamera(camera);
        ModelCamera model_camera = gt_camera;
        model_camera.camera_id = db_image.camera_id;
        input.cameras[db_image.camera_id] = model_camera;
      }
      ModelImage image;
      image.image_id = db_image.image_id;
      image.camera_id = db_image.camera_id;
      image.name = db_image.name;
      image.qvec = gt_image.qvec;
      image.tvec = gt_image.tvec;
      input.images[image.image_id] = image;
    }
  }
  if (input.images.empty()) {
    ThrowError("no image of ",
               database_path,
               " has a ground-truth camera (names differ?)");
  }
  input.WriteText(input_path);
  CreateDirIfNotExists(output_path);
  colmap.Run("point_triangulator",
             {"--database_path",
              work_db,
              "--image_path",
              work_dir,
              "--input_path",
              input_path,
              "--output_path",
              output_path,
              "--Mapper.ba_refine_focal_length",
              "0",
              "--Mapper.ba_refine_principal_point",
              "0",
              "--Mapper.ba_refine_extra_params",
              "0"});
  Reconstruction triangulated;
  triangulated.Read(output_path);
  return triangulated;
}

}  // namespace colmap_gcn
