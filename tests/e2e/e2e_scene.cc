#include "e2e_scene.h"

#include <gtest/gtest.h>

#include <vector>

#include "scene/database.h"
#include "scene/reconstruction.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace test {

std::string IntegrityCheck(const std::string& path) {
  std::string output;
  RunShell("sqlite3 " + ShellQuote(path) + " 'PRAGMA integrity_check;'",
           &output);
  return StringTrim(output);
}

std::set<int64_t> GeometryPairIds(const std::string& path) {
  std::set<int64_t> ids;
  const Database database(path);
  for (const auto& info : database.ReadTwoViewGeometryInfos()) {
    ids.insert(static_cast<int64_t>(info.pair_id));
  }
  return ids;
}

std::string FrontendBinDir() {
  return FrontendExe().substr(0, FrontendExe().find_last_of('/'));
}

int RunFrontend(const std::string& args,
                std::string* output,
                const std::string& env) {
  return RunShell("env " + env + " PATH=" + ShellQuote(FrontendBinDir()) +
                      ":$PATH " + ShellQuote(FrontendExe()) + " " + args,
                  output);
}

void MakeExtractedScene(const std::string& dir,
                        const int num_images,
                        ExtractedScene* scene) {
  scene->scene_path = JoinPaths(dir, "scene");
  scene->image_path = JoinPaths(scene->scene_path, "images");
  scene->database_path = JoinPaths(dir, "base.db");
  std::string output;
  ASSERT_EQ(RunFrontend("gcn_synth --output_path " + scene->scene_path +
                            " --GcnSynth.family ordinary"
                            " --GcnSynth.num_images " +
                            std::to_string(num_images) + " --GcnSynth.seed 1",
                        &output),
            0)
      << output;
  Reconstruction gt;
  gt.ReadText(JoinPaths(scene->scene_path, "gt"));
  ASSERT_FALSE(gt.cameras.empty());
  std::vector<std::string> params;
  for (const double param : gt.cameras.begin()->second.params) {
    params.push_back(std::to_string(param));
  }
  scene->extraction_args =
      " --ImageReader.single_camera 1"
      " --ImageReader.camera_model PINHOLE"
      " --ImageReader.camera_params " +
      StringJoin(params, ",") +
      " --SiftExtraction.max_num_features 2048"
      " --SiftExtraction.use_gpu 0 --SiftExtraction.num_threads 1";
  ASSERT_EQ(RunFrontend("feature_extractor --database_path " +
                            scene->database_path + " --image_path " +
                            scene->image_path + scene->extraction_args,
                        &output),
            0)
      << output;
}

}  // namespace test
}  // namespace colmap_gcn
