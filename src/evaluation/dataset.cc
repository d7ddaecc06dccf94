#include "evaluation/dataset.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "evaluation/bundler.h"
#include "synthetic/scene_generator.h"
#include "util/error.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

namespace fs = std::filesystem;

bool IsModelFolder(const std::string& path) {
  return (ExistsFile(JoinPaths(path, "cameras.txt")) &&
          ExistsFile(JoinPaths(path, "images.txt"))) ||
         (ExistsFile(JoinPaths(path, "cameras.bin")) &&
          ExistsFile(JoinPaths(path, "images.bin")));
}

std::string Basename(std::string path) {
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  return fs::path(path).filename().string();
}

SyntheticSceneOptions SyntheticOptions(const DatasetSpec& spec) {
  SyntheticSceneOptions options;
  options.family = spec.family;
  options.num_images = spec.num_images;
  options.seed = spec.seed;
  return options;
}

void CheckSyntheticSpec(const DatasetSpec& spec) {
  try {
    SyntheticOptions(spec).Check();
  } catch (const Error& error) {
    ThrowError("dataset \"", spec.spec, "\": ", error.what());
  }
}

// The bundle file's "<num_cameras> <num_points>" header line, checked
// without reading the (possibly large) rest.
void CheckBundlerHeader(const std::string& spec, const std::string& path) {
  std::ifstream file(path);
  std::string line;
  while (std::getline(file, line) && StringStartsWith(StringTrim(line), "#")) {
  }
  std::istringstream fields(line);
  long long num_cameras = -1;
  long long num_points = -1;
  std::string rest;
  if (!file || !(fields >> num_cameras >> num_points) || (fields >> rest) ||
      num_cameras < 0 || num_points < 0) {
    ThrowError("dataset ",
               spec,
               ": ",
               path,
               " is not a Bundler file (no \"<cameras> <points>\" header)");
  }
}

void PrepareSynthetic(const std::string& scene_dir, Dataset* dataset) {
  const std::string gt_dir = JoinPaths(scene_dir, "gt");
  const std::string done = JoinPaths(gt_dir, "scene.txt");
  if (!ExistsFile(done)) {
    CheckSyntheticSpec(dataset->spec);
    GenerateSyntheticScene(SyntheticOptions(dataset->spec), scene_dir);
  }
  dataset->kind = "synthetic";
  dataset->image_path = JoinPaths(scene_dir, "images");
  dataset->gt_path = gt_dir;
  dataset->overlap_path = JoinPaths(gt_dir, "pair_overlap.csv");
  dataset->label_source = LabelSource::kSyntheticOverlap;
  dataset->single_camera = true;
}

void Prepare1DSfM(const std::string& scene_dir, Dataset* dataset) {
  const std::string& path = dataset->spec.path;
  std::string bundle_path = JoinPaths(path, "gt_bundle.out");
  if (!ExistsFile(bundle_path)) bundle_path = JoinPaths(path, "bundle.out");
  const std::vector<std::string> listed =
      ReadBundlerImageList(JoinPaths(path, "list.txt"));
  // list.txt paths are relative to the scene folder ("images/x.jpg");
  // COLMAP names are relative to the image folder.
  std::vector<std::string> names;
  for (const std::string& entry : listed) {
    names.push_back(StringStartsWith(entry, "images/") ? entry.substr(7)
                                                       : entry);
  }
  dataset->kind = "1dsfm";
  dataset->image_path = JoinPaths(path, "images");
  const std::string gt_dir = JoinPaths(scene_dir, "gt");
  if (!ExistsFile(JoinPaths(gt_dir, "points3D.txt"))) {
    const BundlerFile bundle = ReadBundlerFile(bundle_path);
    std::vector<std::pair<int, int>> sizes;
    for (size_t i = 0; i < names.size(); ++i) {
      const bool registered =
          i < bundle.cameras.size() && bundle.cameras[i].IsRegistered();
      if (!registered) {
        sizes.emplace_back(0, 0);
        continue;
      }
      const std::string image_file = JoinPaths(dataset->image_path, names[i]);
      const cv::Mat image = cv::imread(image_file, cv::IMREAD_UNCHANGED);
      if (image.empty()) ThrowError("cannot read image ", image_file);
      sizes.emplace_back(image.cols, image.rows);
    }
    BundlerToReconstruction(bundle, names, sizes).WriteText(gt_dir);
  }
  std::ostringstream list;
  for (const std::string& name : names) list << name << "\n";
  dataset->image_list_path = JoinPaths(scene_dir, "image_list.txt");
  WriteFileAtomically(dataset->image_list_path, list.str());
  dataset->image_names = names;
  dataset->gt_path = gt_dir;
  dataset->reference_path = gt_dir;
  dataset->label_source = LabelSource::kReferenceModel;
}

}  // namespace

const char* LabelSourceName(LabelSource source) {
  switch (source) {
    case LabelSource::kSyntheticOverlap:
      return "synthetic overlap";
    case LabelSource::kGroundTruthTriangulation:
      return "GT cameras (triangulated common tracks)";
    case LabelSource::kReferenceModel:
      return "reference model (common tracks)";
    case LabelSource::kExhaustiveReference:
      return "exhaustive reference model (common tracks)";
  }
  return "";
}

DatasetSpec ParseDatasetSpec(const std::string& spec) {
  DatasetSpec parsed;
  parsed.spec = spec;
  if (StringStartsWith(spec, "synth:")) {
    const std::vector<std::string> fields = StringSplit(spec, ":");
    if (fields.size() < 3 || fields.size() > 4) {
      ThrowError("bad dataset \"",
                 spec,
                 "\": expected synth:<family>:<num_images>[:seed]");
    }
    parsed.synthetic = true;
    parsed.family = fields[1];
    try {
      parsed.num_images = std::stoi(fields[2]);
      parsed.seed = fields.size() == 4 ? std::stoi(fields[3]) : 0;
    } catch (const std::exception&) {
      ThrowError("bad dataset \"", spec, "\": numbers expected");
    }
    parsed.name = "synth-" + parsed.family + "-" +
                  std::to_string(parsed.num_images) + "-s" +
                  std::to_string(parsed.seed);
    return parsed;
  }
  if (spec.empty()) ThrowError("empty dataset in --datasets");
  parsed.path = spec;
  parsed.name = Basename(spec);
  return parsed;
}

std::vector<DatasetSpec> ParseDatasetSpecs(const std::string& comma_list) {
  std::vector<DatasetSpec> specs;
  for (const std::string& entry : SplitCommaList(comma_list)) {
    specs.push_back(ParseDatasetSpec(entry));
  }
  if (specs.empty()) ThrowError("--datasets names no dataset");
  for (size_t i = 0; i < specs.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (specs[i].name == specs[j].name) {
        ThrowError("two datasets named ", specs[i].name, " in --datasets");
      }
    }
  }
  return specs;
}

std::vector<std::string> ListImageFiles(const std::string& folder) {
  std::vector<std::string> names;
  if (!ExistsDir(folder)) return names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    std::string extension = entry.path().extension().string();
    std::transform(extension.begin(),
                   extension.end(),
                   extension.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    static const std::vector<std::string> kExtensions = {
        ".jpg", ".jpeg", ".png", ".tif", ".tiff", ".bmp", ".ppm", ".pgm"};
    if (std::find(kExtensions.begin(), kExtensions.end(), extension) !=
        kExtensions.end()) {
      names.push_back(entry.path().filename().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

void CheckDataset(const DatasetSpec& spec) {
  if (spec.synthetic) {
    CheckSyntheticSpec(spec);
    return;
  }
  if (!fs::exists(spec.path)) {
    ThrowError("dataset ", spec.path, " does not exist");
  }
  if (!ExistsDir(spec.path)) {
    ThrowError("dataset ",
               spec.path,
               " is not a folder (images/ + gt/, or 1DSfM list.txt + "
               "bundle.out)");
  }
  const std::string image_path = JoinPaths(spec.path, "images");
  if (!ExistsDir(image_path)) {
    ThrowError("dataset ", spec.path, " has no images/ folder");
  }
  const std::string list_path = JoinPaths(spec.path, "list.txt");
  std::string bundle_path = JoinPaths(spec.path, "gt_bundle.out");
  if (!ExistsFile(bundle_path))
    bundle_path = JoinPaths(spec.path, "bundle.out");
  if (ExistsFile(list_path) && ExistsFile(bundle_path)) {
    const std::vector<std::string> listed = ReadBundlerImageList(list_path);
    size_t num_missing = 0;
    std::string first_missing;
    for (const std::string& entry : listed) {
      if (!ExistsFile(JoinPaths(spec.path, entry)) &&
          !ExistsFile(JoinPaths(image_path, entry))) {
        if (num_missing++ == 0) first_missing = entry;
      }
    }
    if (num_missing > 0) {
      ThrowError("dataset ",
                 spec.path,
                 ": ",
                 num_missing,
                 " of the ",
                 listed.size(),
                 " images in list.txt do not exist (first: \"",
                 first_missing,
                 "\")");
    }
    if (listed.size() < 2) {
      ThrowError("dataset ",
                 spec.path,
                 ": list.txt lists ",
                 listed.size(),
                 " image(s), need >= 2");
    }
    CheckBundlerHeader(spec.path, bundle_path);
    return;
  }
  const size_t num_images = ListImageFiles(image_path).size();
  if (num_images < 2) {
    ThrowError("dataset ",
               spec.path,
               " has ",
               num_images,
               " image(s) in ",
               image_path,
               ", need >= 2");
  }
}

Dataset PrepareDataset(const DatasetSpec& spec, const std::string& scene_dir) {
  Dataset dataset;
  dataset.spec = spec;
  dataset.name = spec.name;
  CreateDirIfNotExists(scene_dir);
  if (spec.synthetic) {
    PrepareSynthetic(scene_dir, &dataset);
  } else {
    if (!ExistsDir(JoinPaths(spec.path, "images"))) {
      ThrowError("dataset ", spec.path, " has no images/ folder");
    }
    const bool has_bundle = ExistsFile(JoinPaths(spec.path, "gt_bundle.out")) ||
                            ExistsFile(JoinPaths(spec.path, "bundle.out"));
    if (ExistsFile(JoinPaths(spec.path, "list.txt")) && has_bundle) {
      Prepare1DSfM(scene_dir, &dataset);
    } else {
      dataset.kind = "images";
      dataset.image_path = JoinPaths(spec.path, "images");
      const std::string gt = JoinPaths(spec.path, "gt");
      const std::string reference = JoinPaths(spec.path, "reference");
      if (IsModelFolder(gt)) {
        dataset.gt_path = gt;
        dataset.label_source = LabelSource::kGroundTruthTriangulation;
      }
      if (IsModelFolder(reference)) {
        dataset.reference_path = reference;
        dataset.label_source = LabelSource::kReferenceModel;
      }
    }
  }
  if (dataset.image_names.empty()) {
    dataset.image_names = ListImageFiles(dataset.image_path);
  }
  std::sort(dataset.image_names.begin(), dataset.image_names.end());
  if (dataset.image_names.size() < 2) {
    ThrowError("dataset ",
               spec.spec,
               " has fewer than 2 images in ",
               dataset.image_path);
  }
  return dataset;
}

}  // namespace colmap_gcn
