#include "controllers/gcn_matching.h"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "controllers/colmap_runner.h"
#include "controllers/gcn_model_pairing.h"
#include "controllers/vocab_tree_pairing.h"
#include "gcn/model_file.h"
#include "retrieval/knn_pairing.h"
#include "scene/database_working_copy.h"
#include "util/error.h"
#include "util/file_lock.h"
#include "util/interrupt.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/timer.h"

namespace colmap_gcn {

void GcnMatchingOptions::Check() const {
  CHECK_OPTION_ONE_OF(
      pairing, "gcn", "exhaustive", "imported", "knn", "vocab_tree");
  CHECK_OPTION_UNSET_OR_GE(k1, -1, "the model's value", 1);
  CHECK_OPTION_UNSET_OR_GE(k2, -1, "the model's value", 1);
  CHECK_OPTION_UNSET_OR_GE(u, -1, "the model's value", 1);
  CHECK_OPTION_UNSET_OR_RANGE(threshold, -1, "the model's value", 0.0, 1.0);
  CHECK_OPTION_GE(min_pairs_per_image, 0);
  CHECK_OPTION_GE(k, 1);
  CHECK_OPTION_NUM_THREADS(num_threads);
  CHECK_OPTION(embedding,
               embedding.empty() || embedding == "vlad" ||
                   embedding == "onnx" || embedding == "vlad+onnx" ||
                   embedding == "imported",
               "be empty (the model's; knn: vlad) or one of vlad, onnx, "
               "vlad+onnx, imported");
  onnx.Check();
  CHECK_OPTION_GE(onnx_batch_size, 1);
  if (embedding == "onnx" || embedding == "vlad+onnx") {
    CHECK_OPTION(
        onnx_path,
        !onnx_path.empty(),
        "name the ONNX network when --GcnMatching.embedding is " + embedding);
    CHECK_OPTION(image_path,
                 !image_path.empty(),
                 "name the image folder (the one given to feature_extractor) "
                 "when --GcnMatching.embedding is " +
                     embedding);
  }
  if (embedding == "imported") {
    CHECK_OPTION(descriptor_path,
                 !descriptor_path.empty(),
                 "name the descriptor file when --GcnMatching.embedding is "
                 "imported");
  }
  if (pairing == "imported") {
    CHECK_OPTION(match_list_path,
                 !match_list_path.empty(),
                 "name a pairs file when --GcnMatching.pairing is imported");
  }
}

void CheckOutputFolder(const std::string& path) {
  if (path.empty()) return;
  const std::filesystem::path parent =
      std::filesystem::absolute(std::filesystem::path(path)).parent_path();
  std::error_code ec;
  if (!std::filesystem::is_directory(parent, ec)) {
    ThrowError(
        "cannot write ", path, ": folder ", parent.string(), " does not exist");
  }
}

std::unique_ptr<GcnPairGenerator> CreateGcnPairGenerator(
    const GcnMatchingOptions& options, const Database& database) {
  const std::string model_path =
      options.model_path.empty() ? DefaultGcnModelPath() : options.model_path;
  if (model_path.empty()) {
    ThrowError(
        "no GCN model: pass --GcnMatching.model_path (train one with colmap "
        "gcn_train) or choose another --GcnMatching.pairing");
  }
  const GcnModel model = ReadGcnModel(model_path);
  GcnPairingOptions pairing = GcnPairingOptionsFromModel(model);
  if (options.k1 > 0) pairing.k1 = options.k1;
  if (options.k2 > 0) pairing.k2 = options.k2;
  if (options.u > 0) pairing.u = options.u;
  if (options.threshold >= 0) pairing.threshold = options.threshold;
  pairing.min_pairs_per_image = options.min_pairs_per_image;
  pairing.num_threads = options.num_threads;
  ModelEmbeddingOptions embedding;
  embedding.embedding = options.embedding;
  embedding.descriptor_path = options.descriptor_path;
  embedding.onnx_path = options.onnx_path;
  embedding.onnx = options.onnx;
  embedding.onnx_batch_size = options.onnx_batch_size;
  embedding.num_threads = options.num_threads;
  std::vector<image_t> image_ids;
  const EmbeddingMatrix embeddings = ComputeModelEmbeddings(
      model, database, embedding, options.image_path, &image_ids);
  return std::make_unique<GcnPairGenerator>(
      pairing, image_ids, embeddings, model);
}

std::unique_ptr<PairGenerator> CreatePairGenerator(
    const GcnMatchingOptions& options, const Database& database) {
  options.Check();
  if (options.pairing == "gcn") {
    return CreateGcnPairGenerator(options, database);
  }
  if (options.pairing == "knn") {
    KnnPairingOptions knn;
    knn.k = options.k;
    knn.num_threads = options.num_threads;
    knn.descriptors.embedding_path = options.embedding_path;
    knn.descriptors.descriptor_path = options.descriptor_path;
    if (options.embedding == "imported") {
      knn.descriptors.embedding = "vlad";  // descriptor_path takes over
    } else if (!options.embedding.empty()) {
      if (!options.descriptor_path.empty()) {
        ThrowError(
            "--GcnMatching.descriptor_path imports descriptors; it "
            "cannot be combined with --GcnMatching.embedding ",
            options.embedding);
      }
      knn.descriptors.embedding = options.embedding;
    }
    knn.descriptors.cnn = options.onnx.ApplyTo(knn.descriptors.cnn);
    knn.descriptors.cnn.onnx_path = options.onnx_path;
    knn.descriptors.cnn.batch_size = options.onnx_batch_size;
    knn.descriptors.image_path = options.image_path;
    return std::make_unique<KnnPairGenerator>(knn, database);
  }
  if (options.pairing == "vocab_tree") {
    VocabTreePairingOptions vocab_tree;
    vocab_tree.k = options.k;
    vocab_tree.vocab_tree_path = options.vocab_tree_path;
    ColmapRunnerOptions runner_options;
    runner_options.log_path = options.colmap_log_path.empty()
                                  ? database.Path() + ".colmap.log"
                                  : options.colmap_log_path;
    runner_options.verbose = options.verbose;
    return std::make_unique<VocabTreePairGenerator>(
        vocab_tree, database, ColmapRunner(runner_options));
  }
  if (options.pairing == "imported") {
    ImagePairsMatchingOptions imported;
    imported.match_list_path = options.match_list_path;
    return std::make_unique<ImportedPairGenerator>(imported, database);
  }
  return std::make_unique<ExhaustivePairGenerator>(ExhaustiveMatchingOptions(),
                                                   database);
}

GcnMatchingReport RunGcnMatching(const std::string& database_path,
                                 const GcnMatchingOptions& options,
                                 const std::vector<std::string>& colmap_args) {
  options.Check();
  const std::string log_path = options.colmap_log_path.empty()
                                   ? database_path + ".colmap.log"
                                   : options.colmap_log_path;
  CheckOutputFolder(log_path);
  CheckOutputFolder(options.pairs_path);
  // Refused before minutes of pairing: a database we cannot replace, or one
  // that another gcn_matcher is working on (the lock spans the whole run).
  const std::string real_path = ResolveDatabasePath(database_path);
  CheckDatabaseWritable(real_path);
  const ScopedFileLock lock(DatabaseLockPath(real_path), database_path);
  GcnMatchingReport report;
  report.pairing = options.pairing;
  const Timer pairing_timer;
  std::vector<ImagePair> pairs;
  std::vector<float> scores;
  {
    const Database database(database_path);
    report.num_images = database.NumImages();
    if (report.num_images < 2) {
      ThrowError(database_path,
                 " has ",
                 report.num_images,
                 " image(s); run colmap feature_extractor first");
    }
    if (database.NumDescriptors() == 0) {
      ThrowError(database_path,
                 " has ",
                 report.num_images,
                 " images but no descriptors; run colmap feature_extractor "
                 "first");
    }
    const std::unique_ptr<PairGenerator> generator =
        CreatePairGenerator(options, database);
    StopPointForTests("pairing");
    pairs = generator->AllPairs();
    // The GCN's scores go into the pairs file for users to inspect.
    if (const auto* gcn =
            dynamic_cast<const GcnPairGenerator*>(generator.get())) {
      for (const ScoredImagePair& pair : gcn->ScoredPairs()) {
        scores.push_back(pair.score);
      }
      const std::string warning =
          GcnKeptEveryCandidateWarning(gcn->Stats(), gcn->Options().k1);
      if (!warning.empty()) LOG(WARNING) << warning;
    }
  }
  report.pairing_seconds = pairing_timer.ElapsedSeconds();

  ColmapRunnerOptions runner_options;
  runner_options.log_path = log_path;
  runner_options.verbose = options.verbose;
  const ColmapRunner colmap(runner_options);

  PairMatchingOptions matching_options;
  matching_options.pairs_path = options.pairs_path;
  matching_options.colmap_args = colmap_args;
  matching_options.scores = scores;
  matching_options.block_size = options.block_size;
  LOG(INFO) << pairs.size() << " pairs from " << options.pairing
            << " pairing of " << report.num_images
            << " images; matching with COLMAP " << colmap.Version();
  report.matching =
      MatchImagePairs(colmap, database_path, pairs, matching_options);
  return report;
}

std::string GcnKeptEveryCandidateWarning(const GcnPairingStats& stats, int k1) {
  if (stats.num_candidates == 0 ||
      stats.num_above_threshold < stats.num_candidates) {
    return "";
  }
  return "all " + std::to_string(stats.num_candidates) +
         " candidate pairs scored above the model's threshold: the GCN "
         "chose nothing beyond each image's k1 = " +
         std::to_string(k1) +
         " nearest neighbours; the model is likely not calibrated for "
         "these images (docs/model_card.md lists what to try)";
}

void PrintGcnMatchingReport(const GcnMatchingReport& report) {
  std::printf("%-12s %8s %8s %8s %8s %10s %10s\n",
              "pairing",
              "images",
              "TAM",
              "UM",
              "UM/TAM",
              "pairing_s",
              "matching_s");
  std::printf("%-12s %8zu %8zu %8zu %8.3f %10.2f %10.2f\n",
              report.pairing.c_str(),
              report.num_images,
              report.matching.num_attempted_pairs,
              report.matching.num_verified_pairs,
              report.matching.UsefulRatio(),
              report.pairing_seconds,
              report.matching.matching_seconds);
  if (report.matching.num_already_matched > 0) {
    std::printf("(%zu of the pairs were already matched in the database)\n",
                report.matching.num_already_matched);
  }
  std::printf("pairs written to %s\n", report.matching.pairs_path.c_str());
}

}  // namespace colmap_gcn
