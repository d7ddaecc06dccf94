#include "scene/database.h"

#include <sqlite3.h>

#include <algorithm>
#include <cstring>
#include <set>

#include "scene/camera_models.h"
#include "scene/database_copy.h"
#include "scene/sqlite_statement.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

// The tables every COLMAP database since 3.x has; our reads need all of them.
const char* const kRequiredTables[] = {"cameras",
                                       "images",
                                       "keypoints",
                                       "descriptors",
                                       "matches",
                                       "two_view_geometries"};

// Tables introduced after 3.8 (pose_priors in 3.9/3.10, rigs/frames in 4.x).
const char* const kNewerTables[] = {
    "pose_priors", "rigs", "rig_sensors", "frames", "frame_data"};

}  // namespace

image_pair_t ImagePairToPairId(image_t image_id1, image_t image_id2) {
  THROW_CHECK(image_id1 < kMaxNumImages && image_id2 < kMaxNumImages);
  if (SwapImagePair(image_id1, image_id2)) {
    std::swap(image_id1, image_id2);
  }
  return kMaxNumImages * image_id1 + image_id2;
}

ImagePair PairIdToImagePair(const image_pair_t pair_id) {
  const image_t image_id2 = static_cast<image_t>(pair_id % kMaxNumImages);
  const image_t image_id1 =
      static_cast<image_t>((pair_id - image_id2) / kMaxNumImages);
  return ImagePair(image_id1, image_id2);
}

bool SwapImagePair(const image_t image_id1, const image_t image_id2) {
  return image_id1 > image_id2;
}

bool IsVerifiedTwoViewGeometry(const int config,
                               const size_t num_inliers,
                               const size_t min_num_inliers) {
  switch (static_cast<TwoViewGeometryConfig>(config)) {
    case TwoViewGeometryConfig::kCalibrated:
    case TwoViewGeometryConfig::kUncalibrated:
    case TwoViewGeometryConfig::kPlanar:
    case TwoViewGeometryConfig::kPanoramic:
    case TwoViewGeometryConfig::kPlanarOrPanoramic:
    case TwoViewGeometryConfig::kMultiple:
      return num_inliers >= min_num_inliers;
    default:
      return false;
  }
}

const char* DatabaseSchemaName(const DatabaseSchema schema) {
  switch (schema) {
    case DatabaseSchema::kColmap38:
      return "COLMAP 3.8";
    case DatabaseSchema::kColmap39Plus:
      return "COLMAP 3.9+";
  }
  return "unknown";
}

Database::Database(const std::string& path, const Mode mode)
    : path_(path), mode_(mode) {
  // sqlite3_open_v2 without SQLITE_OPEN_CREATE would fail on a missing file
  // too, but with a less helpful message; checking first also rejects
  // directories.
  if (!ExistsFile(path_)) {
    ThrowError("database not found: ", path_);
  }
  // Never SQLITE_OPEN_CREATE: opening must not create files. Read-only mode
  // uses SQLITE_OPEN_READONLY so that sqlite itself guarantees we cannot
  // modify a database COLMAP may still be using.
  const int flags = (mode_ == Mode::kReadOnly ? SQLITE_OPEN_READONLY
                                              : SQLITE_OPEN_READWRITE) |
                    SQLITE_OPEN_NOMUTEX;
  const int rc = sqlite3_open_v2(path_.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    const std::string message =
        db_ != nullptr ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    db_ = nullptr;
    ThrowError("cannot open database ", path_, ": ", message);
  }
  // COLMAP may hold a write lock while it matches; wait instead of failing.
  sqlite3_busy_timeout(db_, 10000);
  try {
    DetectSchema();
  } catch (...) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw;
  }
}

Database::~Database() {
  if (db_ != nullptr) {
    sqlite3_close(db_);
  }
}

void Database::DetectSchema() {
  std::set<std::string> tables;
  {
    // sqlite opens any file lazily; the first read is where a non-SQLite
    // file is detected, so translate that into the user-facing message.
    sqlite3_stmt* stmt = nullptr;
    int rc = sqlite3_prepare_v2(
        db_,
        "SELECT name FROM sqlite_master WHERE type = 'table'",
        -1,
        &stmt,
        nullptr);
    while (rc == SQLITE_OK && (rc = sqlite3_step(stmt)) == SQLITE_ROW) {
      tables.insert(
          reinterpret_cast<const char*>(sqlite3_column_text(stmt, 0)));
      rc = SQLITE_OK;
    }
    const std::string message = sqlite3_errmsg(db_);
    const int extended_rc = sqlite3_extended_errcode(db_);
    sqlite3_finalize(stmt);
    // SQLite reports a hot journal on a read-only connection as "attempt to
    // write a readonly database", which would send users after permissions.
    if (extended_rc == SQLITE_READONLY_ROLLBACK) {
      ThrowError(HotJournalMessage(path_));
    }
    if (rc == SQLITE_NOTADB) {
      ThrowError(path_, " is not a COLMAP database (not an SQLite file)");
    }
    if (rc != SQLITE_DONE) {
      ThrowError("cannot read database ", path_, ": ", message);
    }
  }

  std::string missing;
  for (const char* table : kRequiredTables) {
    if (tables.count(table) == 0) {
      missing += (missing.empty() ? "" : ", ") + std::string(table);
    }
  }
  if (!missing.empty()) {
    ThrowError(
        path_, " is not a COLMAP database (missing tables: ", missing, ")");
  }

  bool has_newer_tables = false;
  for (const char* table : kNewerTables) {
    has_newer_tables |= tables.count(table) > 0;
  }
  bool has_image_priors = false;
  {
    SqliteStatement stmt(db_, path_, "PRAGMA table_info(images)");
    while (stmt.Step()) {
      has_image_priors |= stmt.Text(1) == "prior_qw";
    }
  }

  // Newer COLMAP may keep the old prior columns when it migrates a 3.8
  // database, so the new tables decide.
  if (has_newer_tables) {
    schema_ = DatabaseSchema::kColmap39Plus;
  } else if (has_image_priors) {
    schema_ = DatabaseSchema::kColmap38;
  } else {
    ThrowError(path_,
               " has an unrecognised COLMAP database schema (images has no "
               "prior columns and there are no rigs/frames/pose_priors "
               "tables)");
  }
}

void Database::RequireWritable() const {
  if (mode_ != Mode::kReadWrite) {
    ThrowError("database ", path_, " was opened read-only");
  }
}

size_t Database::NumImages() const {
  return SqliteQueryCount(db_, path_, "SELECT COUNT(*) FROM images");
}

size_t Database::NumDescriptors() const {
  return SqliteQueryCount(db_, path_, "SELECT SUM(rows) FROM descriptors");
}

std::vector<DatabaseImage> Database::ReadImagesWhere(
    const std::string& condition) const {
  const std::string sql = "SELECT image_id, name, camera_id FROM images" +
                          (condition.empty() ? "" : " WHERE " + condition) +
                          " ORDER BY image_id";
  SqliteStatement stmt(db_, path_, sql.c_str());
  std::vector<DatabaseImage> images;
  while (stmt.Step()) {
    images.push_back(ReadImageRow(stmt));
  }
  return images;
}

std::vector<DatabaseCamera> Database::ReadAllCameras() const {
  SqliteStatement stmt(db_,
                       path_,
                       "SELECT camera_id, model, width, height, params, "
                       "prior_focal_length FROM cameras ORDER BY camera_id");
  std::vector<DatabaseCamera> cameras;
  while (stmt.Step()) {
    DatabaseCamera camera;
    camera.camera_id = static_cast<camera_t>(stmt.Int64(0));
    camera.model_id = static_cast<int>(stmt.Int64(1));
    camera.width = static_cast<uint64_t>(stmt.Int64(2));
    camera.height = static_cast<uint64_t>(stmt.Int64(3));
    size_t num_bytes = 0;
    const void* data = stmt.Blob(4, &num_bytes);
    if (num_bytes % sizeof(double) != 0) {
      ThrowError("database ",
                 path_,
                 ": params blob of camera ",
                 camera.camera_id,
                 " has ",
                 num_bytes,
                 " bytes, not a multiple of 8");
    }
    camera.params.resize(num_bytes / sizeof(double));
    if (num_bytes > 0) {
      std::memcpy(camera.params.data(), data, num_bytes);
    }
    camera.has_prior_focal_length = stmt.Int64(5) != 0;
    cameras.push_back(std::move(camera));
  }
  return cameras;
}

std::vector<DatabaseImage> Database::ReadAllImages() const {
  return ReadImagesWhere("");
}

FeatureDescriptors Database::ReadDescriptors(const image_t image_id) const {
  SqliteStatement stmt(
      db_,
      path_,
      "SELECT rows, cols, data FROM descriptors WHERE image_id = ?");
  stmt.BindInt64(1, image_id);
  if (!stmt.Step()) {
    return FeatureDescriptors(0, 128);
  }
  return ReadMatrixBlob<FeatureDescriptors>(stmt, 0, "descriptors", image_id);
}

size_t Database::NumDescriptorsForImage(const image_t image_id) const {
  SqliteStatement stmt(
      db_, path_, "SELECT rows FROM descriptors WHERE image_id = ?");
  stmt.BindInt64(1, image_id);
  return stmt.Step() ? static_cast<size_t>(stmt.Int64(0)) : 0;
}

std::vector<TwoViewGeometryInfo> Database::ReadTwoViewGeometryInfos() const {
  // Only the small columns: the blobs would dominate the cost on large
  // databases and callers just need the pair graph.
  SqliteStatement stmt(db_,
                       path_,
                       "SELECT pair_id, config, rows FROM two_view_geometries "
                       "ORDER BY pair_id");
  std::vector<TwoViewGeometryInfo> infos;
  while (stmt.Step()) {
    TwoViewGeometryInfo info;
    info.pair_id = static_cast<image_pair_t>(stmt.Int64(0));
    info.config = static_cast<int>(stmt.Int64(1));
    info.num_inliers = static_cast<size_t>(std::max<int64_t>(0, stmt.Int64(2)));
    infos.push_back(info);
  }
  return infos;
}

std::vector<image_pair_t> Database::ReadMatchesPairIds() const {
  SqliteStatement stmt(
      db_, path_, "SELECT pair_id FROM matches ORDER BY pair_id");
  std::vector<image_pair_t> pair_ids;
  while (stmt.Step()) {
    pair_ids.push_back(static_cast<image_pair_t>(stmt.Int64(0)));
  }
  return pair_ids;
}

std::vector<DatabaseImage> Database::ReadImagesWithoutFeatures() const {
  return ReadImagesWhere(
      "image_id NOT IN (SELECT image_id FROM keypoints) OR "
      "image_id NOT IN (SELECT image_id FROM descriptors)");
}

void Database::UpdateCamera(const DatabaseCamera& camera) {
  RequireWritable();
  const int num_params = CameraModelNumParams(camera.model_id);
  if (num_params < 0 ||
      camera.params.size() != static_cast<size_t>(num_params)) {
    ThrowError("database ",
               path_,
               ": cannot write camera ",
               camera.camera_id,
               " with model id ",
               camera.model_id,
               " and ",
               camera.params.size(),
               " params");
  }
  SqliteStatement stmt(
      db_,
      path_,
      "UPDATE cameras SET model = ?, width = ?, height = ?, "
      "params = ?, prior_focal_length = ? WHERE camera_id = ?");
  stmt.BindInt64(1, camera.model_id);
  stmt.BindInt64(2, static_cast<int64_t>(camera.width));
  stmt.BindInt64(3, static_cast<int64_t>(camera.height));
  stmt.BindBlob(4, camera.params.data(), camera.params.size() * sizeof(double));
  stmt.BindInt64(5, camera.has_prior_focal_length ? 1 : 0);
  stmt.BindInt64(6, camera.camera_id);
  stmt.Execute();
  if (sqlite3_changes(db_) != 1) {
    ThrowError("database ", path_, " has no camera with id ", camera.camera_id);
  }
}

}  // namespace colmap_gcn
