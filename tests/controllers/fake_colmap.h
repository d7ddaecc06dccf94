#pragma once

#include <string>
#include <vector>

#include "controllers/colmap_runner.h"

namespace colmap_gcn {
namespace test {

// A stand-in for the COLMAP binary, for testing what our controllers pass
// to COLMAP and do with its results without running COLMAP: a shell script
// that reports version 3.8 to `help` and otherwise records its arguments;
// `feature_extractor` copies a template database to --database_path,
// `mapper` writes a model without images to <--output_path>/0.
class FakeColmap {
 public:
  // Writes the script and its files into dir (which must exist).
  explicit FakeColmap(const std::string& dir);

  const std::string& Executable() const { return exe_; }

  // A runner on the fake that keeps no log and echoes nothing.
  ColmapRunner Runner() const;

  // The arguments of the last run (the command first); empty before any.
  std::vector<std::string> LastArguments() const;

  // The database feature_extractor "writes": one camera and num_images
  // images in COLMAP 3.8's layout.
  void SetExtractedImages(int num_images) const;

  // Every later run exits 1 after recording its arguments, writing nothing.
  void FailRuns() const;

  // Every later run prints text (as COLMAP logs a failure it goes on from).
  void PrintOnEveryRun(const std::string& text) const;

  // Every later run exits 0 having written nothing, like COLMAP 3.8 when
  // its SQLite writes fail.
  void SkipWrites() const;

  // `mapper` writes model files that do not read back (a full disk).
  void WriteTruncatedModels() const;

  // Like SetExtractedImages, but the last image gets no descriptors.
  void SetImagesWithoutFeatures(int num_images) const;

 private:
  std::string dir_;
  std::string exe_;
};

}  // namespace test
}  // namespace colmap_gcn
