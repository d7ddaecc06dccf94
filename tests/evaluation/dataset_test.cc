#include "evaluation/dataset.h"

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <opencv2/imgcodecs.hpp>

#include "evaluation/bundler.h"
#include "evaluation/bundler_writer.h"
#include "evaluation/common_tracks.h"
#include "scene/camera_models.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

TEST(DatasetSpec, ParsesFoldersAndSynthetic) {
  const DatasetSpec synth = ParseDatasetSpec("synth:repetitive:24:3");
  EXPECT_TRUE(synth.synthetic);
  EXPECT_EQ(synth.family, "repetitive");
  EXPECT_EQ(synth.num_images, 24);
  EXPECT_EQ(synth.seed, 3);
  EXPECT_EQ(synth.name, "synth-repetitive-24-s3");
  EXPECT_EQ(ParseDatasetSpec("synth:ordinary:10").seed, 0);
  const DatasetSpec folder = ParseDatasetSpec("/data/fountain-P11/");
  EXPECT_FALSE(folder.synthetic);
  EXPECT_EQ(folder.name, "fountain-P11");
  EXPECT_THROW(ParseDatasetSpec("synth:ordinary"), Error);
  EXPECT_THROW(ParseDatasetSpec("synth:ordinary:x"), Error);
  EXPECT_THROW(ParseDatasetSpecs("a/x,b/x"), Error);  // same name twice
  EXPECT_EQ(ParseDatasetSpecs("a, synth:ordinary:5").size(), 2u);
}

// A generated scene: n cameras on a ring looking at points on a small
// sphere, PINHOLE cameras with the principal point at the centre, every
// point observed by the cameras in front of it.
Reconstruction MakeScene(int n, int width, int height) {
  Reconstruction model;
  for (int i = 0; i < n; ++i) {
    const image_t id = i + 1;
    ModelCamera camera;
    camera.camera_id = id;
    camera.model_id = CameraModelNameToId("PINHOLE");
    camera.width = width;
    camera.height = height;
    camera.params = {300, 300, width / 2.0, height / 2.0};
    model.cameras[id] = camera;
    const double angle = 2 * M_PI * i / n;
    const Eigen::Vector3d centre(6 * std::cos(angle), 6 * std::sin(angle), 1);
    const Eigen::Vector3d z = (-centre).normalized();
    const Eigen::Vector3d x = Eigen::Vector3d::UnitZ().cross(z).normalized();
    Eigen::Matrix3d rotation;
    rotation.row(0) = x;
    rotation.row(1) = z.cross(x);
    rotation.row(2) = z;
    ModelImage image;
    image.image_id = id;
    image.camera_id = id;
    char name[32];
    std::snprintf(name, sizeof(name), "view_%02d.jpg", i);
    image.name = name;
    const Eigen::Quaterniond q(rotation);
    image.qvec << q.w(), q.x(), q.y(), q.z();
    image.tvec = -rotation * centre;
    model.images[id] = image;
  }
  point3D_t point_id = 1;
  for (int p = 0; p < 200; ++p) {
    const double a = 2 * M_PI * p / 200.0;
    const Eigen::Vector3d xyz(std::cos(a), std::sin(a), 0.3 * std::sin(5 * a));
    ModelPoint3D point;
    point.xyz = xyz;
    for (auto& [id, image] : model.images) {
      // Visible when the point faces the camera (outward normal).
      const Eigen::Vector3d normal(std::cos(a), std::sin(a), 0);
      if (normal.dot(image.ProjectionCenter() - xyz) <= 0) continue;
      const Eigen::Vector3d cam = image.RotationMatrix() * xyz + image.tvec;
      const ModelCamera& camera = model.cameras.at(id);
      TrackElement element;
      element.image_id = id;
      element.point2D_idx = static_cast<point2D_t>(image.points2D.size());
      image.points2D.emplace_back(300 * cam.x() / cam.z() + width / 2.0,
                                  300 * cam.y() / cam.z() + height / 2.0);
      image.point3D_ids.push_back(point_id);
      point.track.push_back(element);
      (void)camera;
    }
    if (!point.track.empty()) model.points3D[point_id++] = point;
  }
  return model;
}

TEST(Dataset, OneDSfMLayoutFromGeneratedScene) {
  const TemporaryDirectory dir;
  const std::string scene = JoinPaths(dir.Path(), "generated-1dsfm");
  const std::string images = JoinPaths(scene, "images");
  CreateDirIfNotExists(images);
  const int width = 160, height = 120;
  const Reconstruction truth = MakeScene(8, width, height);
  // The 1DSfM writer: list.txt order = Bundler camera order; one extra
  // image that Bundler did not register.
  std::vector<std::string> list;
  std::string list_txt;
  for (const auto& [id, image] : truth.images) list.push_back(image.name);
  list.push_back("unregistered.jpg");
  for (const std::string& name : list) {
    cv::imwrite(JoinPaths(images, name),
                cv::Mat(height, width, CV_8UC3, cv::Scalar(80, 120, 160)));
    list_txt += "images/" + name + " 0 300\n";
  }
  WriteFileAtomically(JoinPaths(scene, "list.txt"), list_txt);
  test::WriteBundlerFile(JoinPaths(scene, "gt_bundle.out"),
                         ReconstructionToBundler(truth, list));

  const std::string out = JoinPaths(dir.Path(), "out");
  const Dataset dataset =
      PrepareDataset(ParseDatasetSpec(scene), JoinPaths(out, "scene"));
  EXPECT_EQ(dataset.kind, "1dsfm");
  EXPECT_EQ(dataset.label_source, LabelSource::kReferenceModel);
  EXPECT_EQ(dataset.image_names.size(), 9u);
  EXPECT_FALSE(dataset.image_list_path.empty());
  EXPECT_EQ(dataset.image_path, images);

  Reconstruction converted;
  converted.Read(dataset.gt_path);
  ASSERT_EQ(converted.images.size(), 8u);
  EXPECT_EQ(converted.FindImageWithName("unregistered.jpg"), kInvalidImageId);
  for (const auto& [id, image] : truth.images) {
    const image_t converted_id = converted.FindImageWithName(image.name);
    ASSERT_NE(converted_id, kInvalidImageId) << image.name;
    const ModelImage& other = converted.images.at(converted_id);
    EXPECT_LT((other.ProjectionCenter() - image.ProjectionCenter()).norm(),
              1e-9);
    EXPECT_LT((other.RotationMatrix() - image.RotationMatrix()).norm(), 1e-9);
    const ModelCamera& camera = converted.cameras.at(other.camera_id);
    EXPECT_EQ(camera.width, static_cast<uint64_t>(width));
    EXPECT_DOUBLE_EQ(camera.params[0], 300);
    ASSERT_EQ(other.points2D.size(), image.points2D.size());
    for (size_t i = 0; i < image.points2D.size(); ++i) {
      EXPECT_LT((other.points2D[i] - image.points2D[i]).norm(), 1e-6);
    }
  }
  // Labels from the reference are those of the generated scene.
  const PairLabels from_truth =
      LabelsFromReconstruction(truth, dataset.image_names, "truth");
  const PairLabels from_reference =
      LabelsFromReconstruction(converted, dataset.image_names, "reference");
  EXPECT_FALSE(from_truth.MatchablePairs({}).empty());
  EXPECT_EQ(from_truth.MatchablePairs({}), from_reference.MatchablePairs({}));
  EXPECT_TRUE(from_reference.SharesNothing("view_00.jpg", "unregistered.jpg"));

  // Prepared again: the conversion is cached.
  const Dataset again =
      PrepareDataset(ParseDatasetSpec(scene), JoinPaths(out, "scene"));
  EXPECT_EQ(again.gt_path, dataset.gt_path);
}

TEST(Dataset, ImageFolderWithGroundTruth) {
  const TemporaryDirectory dir;
  const std::string scene = JoinPaths(dir.Path(), "facade");
  CreateDirIfNotExists(JoinPaths(scene, "images"));
  for (const char* name : {"b.png", "a.JPG", "notes.txt"}) {
    WriteFileAtomically(JoinPaths(JoinPaths(scene, "images"), name), "x");
  }
  const std::string out = JoinPaths(dir.Path(), "out");
  Dataset dataset = PrepareDataset(ParseDatasetSpec(scene), out);
  EXPECT_EQ(dataset.kind, "images");
  EXPECT_EQ(dataset.image_names, (std::vector<std::string>{"a.JPG", "b.png"}));
  EXPECT_EQ(dataset.label_source, LabelSource::kExhaustiveReference);
  MakeScene(3, 100, 100).WriteText(JoinPaths(scene, "gt"));
  dataset = PrepareDataset(ParseDatasetSpec(scene), out);
  EXPECT_EQ(dataset.label_source, LabelSource::kGroundTruthTriangulation);
  EXPECT_EQ(dataset.gt_path, JoinPaths(scene, "gt"));
  EXPECT_THROW(
      PrepareDataset(ParseDatasetSpec(JoinPaths(dir.Path(), "none")), out),
      Error);
}

}  // namespace
}  // namespace colmap_gcn
