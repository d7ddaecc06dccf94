#include "synthetic/scene_generator.h"

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "scene/reconstruction.h"
#include "synthetic/pair_overlap.h"
#include "synthetic/random.h"
#include "synthetic/renderer.h"
#include "synthetic/scene_families.h"
#include "synthetic/surface_samples.h"
#include "synthetic/texture.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"
#include "util/threading.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

constexpr int kPinholeModelId = 1;

SyntheticWorld BuildWorld(const std::string& family,
                          const WorldParams& params) {
  if (family == "ordinary") return BuildOrdinaryWorld(params);
  if (family == "repetitive") return BuildRepetitiveWorld(params);
  if (family == "symmetric") return BuildSymmetricWorld(params);
  if (family == "twin_print") return BuildTwinPrintWorld(params);
  if (family == "twin_objects") return BuildTwinObjectsWorld(params);
  ThrowError("unknown synthetic scene family '",
             family,
             "' (expected ordinary, repetitive, symmetric, twin_print or "
             "twin_objects)");
}

void WriteImage(const std::string& path,
                const cv::Mat& image,
                int jpeg_quality) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, image, {cv::IMWRITE_JPEG_QUALITY, jpeg_quality});
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) {
    ThrowError("cannot write image ", path);
  }
}

// Removes images of an earlier run (only our own name patterns).
void RemoveStaleImages(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if ((name.rfind("synth_", 0) == 0 || name.rfind("distractor_", 0) == 0) &&
        entry.path().extension() == ".jpg") {
      fs::remove(entry.path(), ec);
    }
  }
}

}  // namespace

std::string SyntheticImageName(int index) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "synth_%04d.jpg", index);
  return buffer;
}

std::string DistractorImageName(int index) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "distractor_%04d.jpg", index);
  return buffer;
}

void SyntheticSceneOptions::Check() const {
  CHECK_OPTION_ONE_OF(family,
                      "ordinary",
                      "repetitive",
                      "symmetric",
                      "twin_print",
                      "twin_objects");
  CHECK_OPTION_RANGE(num_images, 2, 100000);
  CHECK_OPTION_RANGE(num_distractors, 0, 100000);
  CHECK_OPTION_RANGE(width, 16, 16384);
  CHECK_OPTION_RANGE(height, 16, 16384);
  CHECK_OPTION_INTERVAL(focal_length_factor, 0.05, false, 100.0, false);
  CHECK_OPTION_GE(seed, 0);
  CHECK_OPTION_NUM_THREADS(num_threads);
  CHECK_OPTION_RANGE(num_surface_samples, 100, 50000000);
  CHECK_OPTION_RANGE(symmetric_sides, 3, 64);
  CHECK_OPTION_INTERVAL(min_view_cosine, 0.0, true, 1.0, false);
  CHECK_OPTION_RANGE(jpeg_quality, 1, 100);
}

namespace {

// The ground truth as a COLMAP model: image i's camera and, as its 2D
// points, the surface samples it sees (one 3D point per sample seen).
Reconstruction GroundTruthModel(
    const SyntheticSceneOptions& options,
    const SyntheticWorld& world,
    const std::vector<SurfaceSample>& samples,
    const std::vector<std::vector<SampleObservation>>& visible,
    size_t* num_observations) {
  Reconstruction model;
  ModelCamera model_camera;
  model_camera.camera_id = 1;
  model_camera.model_id = kPinholeModelId;
  model_camera.width = options.width;
  model_camera.height = options.height;
  const PinholeCamera& first = world.cameras[0];
  model_camera.params = {first.fx, first.fy, first.cx, first.cy};
  model.cameras[1] = model_camera;

  std::vector<point3D_t> point_ids(samples.size(), kInvalidPoint3DId);
  point3D_t next_point_id = 1;
  for (int i = 0; i < static_cast<int>(visible.size()); ++i) {
    const PinholeCamera& camera = world.cameras[i];
    ModelImage image;
    image.image_id = static_cast<image_t>(i + 1);
    image.qvec = camera.Qvec();
    image.tvec = camera.t;
    image.camera_id = 1;
    image.name = SyntheticImageName(i);
    for (const SampleObservation& observation : visible[i]) {
      point3D_t& point_id = point_ids[observation.sample_idx];
      if (point_id == kInvalidPoint3DId) {
        point_id = next_point_id++;
        ModelPoint3D point;
        const SurfaceSample& sample = samples[observation.sample_idx];
        point.xyz = sample.xyz;
        // Sample colours are BGR.
        for (int c = 0; c < 3; ++c) {
          point.color(c) = static_cast<uint8_t>(
              std::clamp(std::lround(sample.color(2 - c)), 0L, 255L));
        }
        point.error = 0.0;
        model.points3D[point_id] = point;
      }
      TrackElement element;
      element.image_id = image.image_id;
      element.point2D_idx = static_cast<point2D_t>(image.points2D.size());
      model.points3D[point_id].track.push_back(element);
      image.points2D.push_back(observation.xy);
      image.point3D_ids.push_back(point_id);
    }
    *num_observations += image.points2D.size();
    model.images[image.image_id] = std::move(image);
  }
  return model;
}

// Every pair's overlap from the samples each image sees (visibility bitsets);
// distractors share nothing with anything.
PairOverlapTable VisibilityOverlaps(
    const std::vector<std::vector<SampleObservation>>& visible,
    size_t num_samples,
    int num_distractors,
    size_t* num_pairs_overlap_03) {
  const int num_images = static_cast<int>(visible.size());
  const size_t num_words = (num_samples + 63) / 64;
  std::vector<std::vector<uint64_t>> bits(num_images,
                                          std::vector<uint64_t>(num_words, 0));
  for (int i = 0; i < num_images; ++i) {
    for (const SampleObservation& observation : visible[i]) {
      bits[i][observation.sample_idx / 64] |= 1ULL
                                              << (observation.sample_idx % 64);
    }
  }
  std::vector<std::string> names;
  std::vector<int> num_visible;
  for (int i = 0; i < num_images; ++i) {
    names.push_back(SyntheticImageName(i));
    num_visible.push_back(static_cast<int>(visible[i].size()));
  }
  for (int d = 0; d < num_distractors; ++d) {
    names.push_back(DistractorImageName(d));
    num_visible.push_back(0);
  }
  PairOverlapTable table;
  for (size_t i = 0; i < names.size(); ++i) {
    for (size_t j = i + 1; j < names.size(); ++j) {
      PairOverlap pair;
      pair.name1 = names[i];
      pair.name2 = names[j];
      pair.num_visible1 = num_visible[i];
      pair.num_visible2 = num_visible[j];
      if (static_cast<int>(j) < num_images) {
        int shared = 0;
        for (size_t w = 0; w < num_words; ++w) {
          shared += __builtin_popcountll(bits[i][w] & bits[j][w]);
        }
        pair.num_shared = shared;
        pair.overlap12 =
            pair.num_visible1 > 0 ? double(shared) / pair.num_visible1 : 0.0;
        pair.overlap21 =
            pair.num_visible2 > 0 ? double(shared) / pair.num_visible2 : 0.0;
      }
      if (pair.MinOverlap() >= 0.3) {
        ++*num_pairs_overlap_03;
      }
      table.Add(pair);
    }
  }
  return table;
}

}  // namespace

SyntheticSceneSummary GenerateSyntheticScene(
    const SyntheticSceneOptions& options, const std::string& output_path) {
  const Timer timer;
  options.Check();
  if (output_path.empty()) {
    ThrowError("output_path is empty");
  }
  const int num_threads = EffectiveNumThreads(options.num_threads);
  std::vector<cv::Mat> user_textures;
  if (!options.texture_dir.empty()) {
    user_textures = ReadTextureImages(options.texture_dir);
  }

  const uint64_t seed =
      SyntheticRandom::Mix(0xC01A9ULL, static_cast<uint64_t>(options.seed));
  WorldParams params;
  params.num_images = options.num_images;
  params.width = options.width;
  params.height = options.height;
  params.focal_length =
      options.focal_length_factor * std::max(options.width, options.height);
  params.seed = seed;
  params.texture_scale = std::max(options.width, options.height) / 640.0;
  params.num_user_textures = static_cast<int>(user_textures.size());
  params.symmetric_sides = options.symmetric_sides;
  SyntheticWorld world = BuildWorld(options.family, params);
  world.scene.GenerateTextures(user_textures, num_threads);
  const std::vector<SurfaceSample> samples =
      SampleSurfaces(world.scene, options.num_surface_samples, seed);

  const std::string image_dir = JoinPaths(output_path, "images");
  const std::string gt_dir = JoinPaths(output_path, "gt");
  CreateDirIfNotExists(image_dir);
  CreateDirIfNotExists(gt_dir);
  RemoveStaleImages(image_dir);

  // Scene images: render and compute the visible samples, in parallel.
  const int num_images = options.num_images;
  std::vector<std::vector<SampleObservation>> visible(num_images);
  ParallelFor(0, num_images, num_threads, [&](int i) {
    const PinholeCamera& camera = world.cameras[i];
    SyntheticRandom rng(SyntheticRandom::Mix(seed, 1000003ULL + i));
    const PhotometricParams photometric = options.photometric_variation
                                              ? PhotometricParams::Random(&rng)
                                              : PhotometricParams();
    WriteImage(JoinPaths(image_dir, SyntheticImageName(i)),
               RenderImage(world.scene, camera, photometric),
               options.jpeg_quality);
    const TriangleBins bins(world.scene, camera);
    visible[i] = ComputeVisibleSamples(
        world.scene, bins, camera, samples, options.min_view_cosine);
  });

  // Distractors: each from its own unrelated little world.
  ParallelFor(0, options.num_distractors, num_threads, [&](int d) {
    WorldParams distractor_params = params;
    distractor_params.num_images = 1;
    distractor_params.seed = SyntheticRandom::Mix(seed, 2000003ULL + d);
    SyntheticWorld distractor = BuildDistractorWorld(distractor_params);
    distractor.scene.GenerateTextures(user_textures, 1);
    SyntheticRandom rng(SyntheticRandom::Mix(seed, 3000017ULL + d));
    const PhotometricParams photometric = options.photometric_variation
                                              ? PhotometricParams::Random(&rng)
                                              : PhotometricParams();
    WriteImage(
        JoinPaths(image_dir, DistractorImageName(d)),
        RenderImage(distractor.scene, distractor.cameras[0], photometric),
        options.jpeg_quality);
  });

  SyntheticSceneSummary summary;
  const Reconstruction model = GroundTruthModel(
      options, world, samples, visible, &summary.num_observations);
  model.WriteText(gt_dir);

  const PairOverlapTable table =
      VisibilityOverlaps(visible,
                         samples.size(),
                         options.num_distractors,
                         &summary.num_pairs_overlap_03);
  WritePairOverlapTable(table, JoinPaths(gt_dir, "pair_overlap.csv"));

  std::string distractor_list;
  for (int d = 0; d < options.num_distractors; ++d) {
    distractor_list += DistractorImageName(d) + "\n";
  }
  WriteFileAtomically(JoinPaths(gt_dir, "distractors.txt"), distractor_list);

  for (int i = 0; i < num_images; ++i) {
    for (int j = i + 1; j < num_images; ++j) {
      summary.scene_size = std::max(
          summary.scene_size,
          (world.cameras[i].Center() - world.cameras[j].Center()).norm());
    }
  }
  std::ostringstream info;
  info.precision(17);
  info << "family " << options.family << "\n"
       << "seed " << options.seed << "\n"
       << "num_images " << num_images << "\n"
       << "num_distractors " << options.num_distractors << "\n"
       << "width " << options.width << "\n"
       << "height " << options.height << "\n"
       << "focal_length " << params.focal_length << "\n"
       << "num_surface_samples " << samples.size() << "\n"
       << "num_symmetric_sides " << world.num_symmetric_sides << "\n"
       << "scene_size " << summary.scene_size << "\n"
       << "target " << world.target.x() << " " << world.target.y() << " "
       << world.target.z() << "\n";
  WriteFileAtomically(JoinPaths(gt_dir, "scene.txt"), info.str());

  summary.num_images = num_images;
  summary.num_distractors = options.num_distractors;
  summary.num_points3D = model.points3D.size();
  summary.num_pairs = table.NumPairs();
  summary.seconds = timer.ElapsedSeconds();
  return summary;
}

}  // namespace colmap_gcn
