#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "util/types.h"

struct sqlite3;
struct sqlite3_stmt;

namespace colmap_gcn {

// COLMAP's pair-id encoding (scene/database.cc): the smaller id first.
const uint64_t kMaxNumImages = 2147483647;
image_pair_t ImagePairToPairId(image_t image_id1, image_t image_id2);
ImagePair PairIdToImagePair(image_pair_t pair_id);
// True if the pair must be swapped to put the smaller id first, as COLMAP
// stores matches with column 0 indexing the smaller image id.
bool SwapImagePair(image_t image_id1, image_t image_id2);

typedef Eigen::Matrix<uint8_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
    FeatureDescriptors;  // rows x 128 (SIFT)

// Two-view geometry configurations (estimators/two_view_geometry.h).
enum class TwoViewGeometryConfig : int {
  kUndefined = 0,
  kDegenerate = 1,
  kCalibrated = 2,
  kUncalibrated = 3,
  kPlanar = 4,
  kPanoramic = 5,
  kPlanarOrPanoramic = 6,
  kWatermark = 7,
  kMultiple = 8,
};

// COLMAP's default --SiftMatching.min_num_inliers.
constexpr int kDefaultMinNumInliers = 15;

// The one rule for a verified pair, as COLMAP's mapper sees it: its config
// is one of {2,3,4,5,6,8} and it has at least min_num_inliers inlier
// matches.
bool IsVerifiedTwoViewGeometry(int config,
                               size_t num_inliers,
                               size_t min_num_inliers = kDefaultMinNumInliers);

struct DatabaseCamera {
  camera_t camera_id = kInvalidCameraId;
  int model_id = -1;
  uint64_t width = 0;
  uint64_t height = 0;
  std::vector<double> params;
  bool has_prior_focal_length = false;
};

struct DatabaseImage {
  image_t image_id = kInvalidImageId;
  std::string name;
  camera_t camera_id = kInvalidCameraId;
};

// Summary row of the two_view_geometries table.
struct TwoViewGeometryInfo {
  image_pair_t pair_id = kInvalidImagePairId;
  int config = 0;
  size_t num_inliers = 0;
};

// The database layouts we recognise.
enum class DatabaseSchema {
  kColmap38,      // COLMAP <= 3.8: images carry prior_q*/prior_t* columns
  kColmap39Plus,  // COLMAP 3.9 - 4.x: rigs/frames/pose_priors tables
};

const char* DatabaseSchemaName(DatabaseSchema schema);

// Access to a COLMAP SQLite database through the sqlite3 C API. Opening
// verifies that the file exists, is SQLite and has COLMAP's tables, and
// throws Error with a one-line message otherwise; nothing is ever created by
// opening. Read-only unless opened with kReadWrite.
//
// Read-only mode uses SQLITE_OPEN_READONLY and never modifies the database
// file. COLMAP creates its databases in WAL journal mode, for which sqlite
// still creates (empty) "<path>-wal" and "<path>-shm" side files next to the
// database on a read-only open if they do not exist; they are harmless and
// are not removed, since a concurrent COLMAP process may be using them.
//
// Reads for a missing row return empty results (0 rows); blobs whose size
// does not match their rows/cols throw Error. Not thread-safe: use one
// Database per thread.
class Database {
 public:
  enum class Mode { kReadOnly, kReadWrite };

  explicit Database(const std::string& path, Mode mode = Mode::kReadOnly);
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  const std::string& Path() const { return path_; }
  DatabaseSchema Schema() const { return schema_; }

  size_t NumImages() const;
  size_t NumDescriptors() const;  // summed over images

  // Throws Error for a params blob that is not a whole number of doubles.
  std::vector<DatabaseCamera> ReadAllCameras() const;  // ordered by camera_id
  std::vector<DatabaseImage> ReadAllImages() const;    // ordered by image_id

  FeatureDescriptors ReadDescriptors(image_t image_id) const;
  size_t NumDescriptorsForImage(image_t image_id) const;

  // Only pair_id, config and rows (no blobs), ordered by pair_id.
  std::vector<TwoViewGeometryInfo> ReadTwoViewGeometryInfos() const;

  // The pair ids that have a matches row (with any number of matches),
  // ordered.
  std::vector<image_pair_t> ReadMatchesPairIds() const;

  // Images lacking a keypoints or a descriptors row (a row with zero
  // features counts: COLMAP writes one for a featureless image), ordered by
  // image_id.
  std::vector<DatabaseImage> ReadImagesWithoutFeatures() const;

  // Writing (requires kReadWrite). Used to set ground-truth intrinsics before
  // point_triangulator.
  void UpdateCamera(const DatabaseCamera& camera);

 protected:
  // The check of every row COLMAP relies on reads tables this class has no
  // reader for.
  friend void ValidateDatabaseForColmap(const Database& database);

  // For test readers (tests/scene/database_inspector.h) that need tables the
  // library itself never reads; owned by this object.
  sqlite3* Handle() const { return db_; }

 private:
  void DetectSchema();
  // The images rows matching an SQL condition ("" for all), by image_id.
  std::vector<DatabaseImage> ReadImagesWhere(
      const std::string& condition) const;
  void RequireWritable() const;

  std::string path_;
  Mode mode_;
  sqlite3* db_ = nullptr;
  DatabaseSchema schema_ = DatabaseSchema::kColmap38;
};

}  // namespace colmap_gcn
