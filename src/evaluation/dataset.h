#pragma once

#include <string>
#include <vector>

namespace colmap_gcn {

// Where a scene's ground-truth pair labels come from.
enum class LabelSource {
  kSyntheticOverlap,  // generator's exact overlaps (gt/pair_overlap.csv)
  kGroundTruthTriangulation,  // matches triangulated on the GT cameras
  kReferenceModel,       // common tracks of a given reference reconstruction
  kExhaustiveReference,  // common tracks of the exhaustive method's model
};

const char* LabelSourceName(LabelSource source);

// A --datasets entry: a scene folder, or "synth:<family>:<n>[:seed]".
struct DatasetSpec {
  std::string spec;
  std::string name;  // folder name, or "synth-<family>-<n>-s<seed>"
  std::string path;  // the folder (empty for synthetic)
  bool synthetic = false;
  std::string family;
  int num_images = 0;
  int seed = 0;
};

// Throws Error on a malformed spec.
DatasetSpec ParseDatasetSpec(const std::string& spec);
std::vector<DatasetSpec> ParseDatasetSpecs(const std::string& comma_list);

// A scene ready for the benchmark. Layouts recognised:
//  - image folder: <path>/images, optional <path>/gt (COLMAP model of the
//    ground-truth cameras, as in ../shared/datasets) and optional
//    <path>/reference (COLMAP model with points used for labels);
//  - 1DSfM: <path>/images, <path>/list.txt and <path>/gt_bundle.out or
//    <path>/bundle.out (converted to a COLMAP model that serves as both
//    ground-truth cameras and reference reconstruction);
//  - synthetic: rendered into the scene's output folder by gcn_synth.
struct Dataset {
  DatasetSpec spec;
  std::string name;
  std::string kind;        // "images", "1dsfm" or "synthetic"
  std::string image_path;  // folder given to feature_extractor
  // Image names (relative to image_path) to extract, sorted; all images
  // in image_path when it is the whole folder.
  std::vector<std::string> image_names;
  // Non-empty when only a listed subset is to be extracted (1DSfM).
  std::string image_list_path;
  std::string gt_path;         // COLMAP model of GT cameras, or ""
  std::string reference_path;  // COLMAP model with points, or ""
  std::string overlap_path;    // pair_overlap.csv, or ""
  LabelSource label_source = LabelSource::kExhaustiveReference;
  // Extract with one shared camera (synthetic scenes are rendered so).
  bool single_camera = false;
};

// Throws Error naming the spec when the dataset cannot be prepared: a bad
// synthetic family or size, a missing path or one that is not a folder, no
// images/ or fewer than 2 images, a list.txt naming missing images, a
// bundle file without a Bundler header. Cheap: nothing is rendered or
// converted, so the benchmark checks every dataset before any work.
void CheckDataset(const DatasetSpec& spec);

// Prepares the dataset in scene_dir (OUT/<name>): renders synthetic scenes,
// converts Bundler references to COLMAP models, lists the images. Work
// whose outputs exist is not repeated. Throws Error on a missing or
// malformed layout.
Dataset PrepareDataset(const DatasetSpec& spec, const std::string& scene_dir);

// Image file names (jpg, jpeg, png, tif, tiff, bmp, ppm, pgm; any case)
// directly in a folder, sorted.
std::vector<std::string> ListImageFiles(const std::string& folder);

}  // namespace colmap_gcn
