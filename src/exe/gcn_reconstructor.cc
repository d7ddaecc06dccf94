#include "exe/gcn_reconstructor.h"

#include <algorithm>
#include <cstdio>
#include <utility>
#include <vector>

#include "controllers/colmap_runner.h"
#include "controllers/feature_extraction.h"
#include "controllers/gcn_matching.h"
#include "controllers/incremental_mapping.h"
#include "evaluation/html_report.h"
#include "evaluation/json_file.h"
#include "exe/gcn_matcher.h"
#include "scene/database_copy.h"
#include "scene/reconstruction.h"
#include "scene/reconstruction_stats.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

// The run as the report shows it: the command line, the options given on
// it, the stages' times and the matching counts.
Json RunSummary(int argc,
                char** argv,
                const ColmapRunner& colmap,
                const GcnMatchingOptions& matching_options,
                const std::string& database_path,
                const std::vector<std::pair<std::string, double>>& stages,
                const GcnMatchingReport& matching) {
  std::vector<std::string> command = {"colmap"};
  Json settings = Json::object();
  for (int i = 0; i < argc; ++i) {
    command.push_back(ShellQuote(argv[i]));
    const std::string arg = argv[i];
    if (StringStartsWith(arg, "--") && i + 1 < argc) {
      settings[arg.substr(2)] = argv[i + 1];
    }
  }
  settings["GcnMatching.pairing"] = matching_options.pairing;
  settings["COLMAP"] = colmap.Executable() + " " + colmap.Version();
  Json run;
  run["command"] = StringJoin(command, " ");
  run["settings"] = settings;
  run["pairing"] = matching_options.pairing;
  run["num_images"] = matching.num_images;
  run["tam"] = matching.matching.num_attempted_pairs;
  run["um"] = matching.matching.num_verified_pairs;
  run["pairs_path"] = matching_options.matching.pairs_path.empty()
                          ? database_path + ".pairs.txt"
                          : matching_options.matching.pairs_path;
  Json times = Json::array();
  for (const auto& [name, seconds] : stages) {
    times.push_back({{"name", name}, {"seconds", seconds}});
  }
  run["stages"] = times;
  return run;
}

// The models' table; returns the largest model's registered images.
size_t PrintModels(const std::vector<std::string>& model_paths,
                   size_t num_images) {
  std::printf("%-28s %10s %8s %12s %10s %10s\n",
              "model",
              "registered",
              "points",
              "observations",
              "track_len",
              "reproj_px");
  size_t largest = 0;
  for (const std::string& model_path : model_paths) {
    Reconstruction reconstruction;
    reconstruction.Read(model_path);
    const ReconstructionStatistics stats =
        ComputeReconstructionStatistics(reconstruction);
    largest = std::max(largest, stats.num_registered_images);
    std::printf("%-28s %5zu/%-4zu %8zu %12zu %10.2f %10.3f\n",
                model_path.c_str(),
                stats.num_registered_images,
                num_images,
                stats.num_points3D,
                stats.num_observations,
                stats.mean_track_length,
                stats.mean_reprojection_error);
  }
  return largest;
}

// What the pair selection saved, at the matching rate measured in this run.
void PrintSummary(const GcnMatchingReport& matching,
                  size_t registered,
                  const std::string& report_path) {
  const size_t n = matching.num_images;
  const size_t exhaustive = n * (n - 1) / 2;
  const size_t tam = matching.matching.num_attempted_pairs;
  const double seconds = matching.matching.matching_seconds;
  std::printf("\nsummary\n");
  std::printf(
      "  pairs matched     %zu of the %zu an exhaustive matching "
      "tries (%.0f %%), %zu verified\n",
      tam,
      exhaustive,
      exhaustive == 0 ? 0.0 : 100.0 * tam / exhaustive,
      matching.matching.num_verified_pairs);
  if (tam > 0 && seconds > 0) {
    const double per_pair = seconds / tam;
    const double exhaustive_seconds = per_pair * exhaustive;
    std::printf(
        "  matching time     %.1f s (%.2f s per pair, measured); "
        "exhaustive at that rate: ~%.0f s\n",
        seconds,
        per_pair,
        exhaustive_seconds);
    // Every pair matched: nothing saved (and no "-0 s").
    const double saved =
        std::max(0.0, exhaustive_seconds - seconds - matching.pairing_seconds);
    std::printf(
        "  time saved        ~%.0f s (pair selection itself took "
        "%.1f s)\n",
        saved,
        matching.pairing_seconds);
  }
  std::printf(
      "  registered        %zu of %zu images (largest model)\n", registered, n);
  std::printf("  report            %s\n", report_path.c_str());
}

}  // namespace

int RunGcnReconstructor(int argc, char** argv) {
  std::string image_path;
  std::string workspace_path;
  GcnMatchingOptions matching_options;
  FeatureExtractionOptions extraction_options;
  IncrementalMappingOptions mapping_options;
  OptionManager manager(
      "gcn_reconstructor",
      "Extracts features, matches the pairs gcn_matcher selects and maps: "
      "<workspace_path>/database.db and <workspace_path>/sparse/N.");
  manager.AddRequiredOption("image_path", &image_path);
  manager.AddRequiredOption("workspace_path", &workspace_path);
  AddGcnMatchingOptions(&manager, &matching_options);
  // COLMAP's options that we set ourselves: read here, passed once.
  manager.AddDefaultOption("ImageReader.single_camera",
                           &extraction_options.single_camera,
                           "one camera for all images");
  manager.AddDefaultOption("Mapper.num_threads",
                           &mapping_options.num_threads,
                           "mapper threads; -1: all cores");
  manager.AddDefaultOption("Mapper.min_model_size",
                           &mapping_options.min_model_size,
                           "smaller models are discarded by the mapper");
  manager.AddPassThroughPrefix("SiftMatching.");
  manager.AddPassThroughPrefix("ImageReader.");
  manager.AddPassThroughPrefix("SiftExtraction.");
  manager.AddPassThroughPrefix("Mapper.");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] {
    matching_options.Check();
    CHECK_OPTION_NUM_THREADS(mapping_options.num_threads);
    CHECK_OPTION_GE(mapping_options.min_model_size, 0);
  });
  // COLMAP's own options are checked by COLMAP before anything runs.
  CheckColmapArguments(manager.PassThroughArguments());
  CheckImageFolder(image_path);
  CheckOutputFolder(matching_options.matching.colmap_log_path);
  CheckOutputFolder(matching_options.matching.pairs_path);
  CreateDirIfNotExists(workspace_path);
  const std::string database_path = JoinPaths(workspace_path, "database.db");
  const std::string sparse_path = JoinPaths(workspace_path, "sparse");
  const auto& args = manager.PassThroughArguments();

  ColmapRunnerOptions runner_options;
  runner_options.log_path = JoinPaths(workspace_path, "colmap.log");
  runner_options.verbose = matching_options.matching.verbose;
  const ColmapRunner colmap(runner_options);
  if (matching_options.matching.colmap_log_path.empty()) {
    matching_options.matching.colmap_log_path = runner_options.log_path;
  }

  LOG(INFO) << "[1/3] feature_extractor";
  extraction_options.image_path = image_path;
  extraction_options.colmap_args =
      ArgumentsWithPrefix(args, {"ImageReader.", "SiftExtraction."});
  const FeatureExtractionSummary extraction =
      ExtractFeatures(colmap, database_path, extraction_options);

  LOG(INFO) << "[2/3] gcn_matcher";
  matching_options.colmap_args = ArgumentsWithPrefix(args, {"SiftMatching."});
  const GcnMatchingReport matching =
      RunGcnMatching(database_path, matching_options);

  LOG(INFO) << "[3/3] mapper";
  if (!ListSparseModels(sparse_path).empty()) {
    ThrowError(sparse_path,
               " already holds models; use a new --workspace_path");
  }
  mapping_options.image_path = image_path;
  mapping_options.colmap_args = ArgumentsWithPrefix(args, {"Mapper."});
  const IncrementalMappingSummary mapping = RunIncrementalMapping(
      colmap, database_path, sparse_path, mapping_options);

  const double choosing_seconds = matching.pairing_seconds;
  const double matching_seconds =
      std::max(0.0, matching.matching.matching_seconds);
  WriteJsonFile(JoinPaths(workspace_path, kRunSummaryFile),
                RunSummary(argc,
                           argv,
                           colmap,
                           matching_options,
                           database_path,
                           {{"feature extraction", extraction.seconds},
                            {"pair selection", choosing_seconds},
                            {"matching and verification", matching_seconds},
                            {"mapping", mapping.seconds}},
                           matching));
  HtmlReportOptions report_options;
  report_options.workspace_path = workspace_path;
  report_options.min_num_inliers = matching_options.matching.min_num_inliers;
  const std::string report_path = WriteHtmlReport(report_options);
  // Our reads beside COLMAP's mapper leave an empty "-wal" and "-shm".
  RemoveEmptySqliteSideFiles(database_path);

  PrintGcnMatchingReport(matching);
  std::printf("\nextraction %.1f s, matching %.1f s, mapping %.1f s\n",
              extraction.seconds,
              matching.matching.matching_seconds,
              mapping.seconds);
  const size_t registered =
      PrintModels(mapping.model_paths, matching.num_images);
  PrintSummary(matching, registered, report_path);
  if (mapping.model_paths.empty()) {
    std::printf("(the mapper produced no model)\n");
    return 1;
  }
  return 0;
}

}  // namespace colmap_gcn
