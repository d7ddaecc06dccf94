#include "scene/two_view_geometry_store.h"

#include <sqlite3.h>

#include <cstring>

#include "scene/sqlite_statement.h"
#include "util/error.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

// A 3x3 float64 blob (COLMAP stores F, E, H row-major); zero when absent.
Eigen::Matrix3d ReadMatrix3Blob(const SqliteStatement& stmt, const int col) {
  size_t num_bytes = 0;
  const void* data = stmt.Blob(col, &num_bytes);
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> matrix =
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor>::Zero();
  if (data != nullptr && num_bytes == 9 * sizeof(double)) {
    std::memcpy(matrix.data(), data, num_bytes);
  }
  return matrix;
}

// Runs a statement without results.
void Run(sqlite3* db, const std::string& path, const std::string& sql) {
  SqliteStatement stmt(db, path, sql.c_str());
  stmt.Execute();
}

// Commits on success, rolls back when an exception leaves the scope.
class Transaction {
 public:
  Transaction(sqlite3* db, const std::string& path) : db_(db), path_(path) {
    Run(db_, path_, "BEGIN IMMEDIATE");
  }
  ~Transaction() {
    if (!committed_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void Commit() {
    Run(db_, path_, "COMMIT");
    committed_ = true;
  }

 private:
  sqlite3* db_;
  const std::string& path_;
  bool committed_ = false;
};

}  // namespace

TwoViewGeometryStore::TwoViewGeometryStore(const std::string& path,
                                           const Mode mode)
    : Database(path, mode), writable_(mode == Mode::kReadWrite) {}

Eigen::Matrix<float, Eigen::Dynamic, 2>
TwoViewGeometryStore::ReadKeypointPositions(const image_t image_id) const {
  SqliteStatement stmt(Handle(),
                       Path(),
                       "SELECT rows, cols, data FROM keypoints WHERE "
                       "image_id = ?");
  stmt.BindInt64(1, image_id);
  if (!stmt.Step()) return Eigen::Matrix<float, Eigen::Dynamic, 2>();
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
      keypoints = ReadMatrixBlob<
          Eigen::
              Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          stmt, 0, "keypoints", image_id);
  if (keypoints.rows() > 0 && keypoints.cols() < 2) {
    ThrowError("database ",
               Path(),
               ": keypoints of image ",
               image_id,
               " have ",
               keypoints.cols(),
               " columns");
  }
  return keypoints.leftCols(std::min<Eigen::Index>(2, keypoints.cols()));
}

FeatureMatches TwoViewGeometryStore::ReadMatches(
    const image_pair_t pair_id) const {
  SqliteStatement stmt(
      Handle(),
      Path(),
      "SELECT rows, cols, data FROM matches WHERE pair_id = ?");
  stmt.BindInt64(1, static_cast<int64_t>(pair_id));
  if (!stmt.Step()) return FeatureMatches();
  return ReadMatrixBlob<FeatureMatches>(
      stmt, 0, "matches", static_cast<int64_t>(pair_id));
}

std::vector<VerifiedTwoViewGeometry>
TwoViewGeometryStore::ReadVerifiedTwoViewGeometries(
    const size_t min_num_inliers) const {
  SqliteStatement stmt(Handle(),
                       Path(),
                       "SELECT pair_id, rows, cols, data, config, F, E, H FROM "
                       "two_view_geometries ORDER BY pair_id");
  std::vector<VerifiedTwoViewGeometry> pairs;
  while (stmt.Step()) {
    const int config = static_cast<int>(stmt.Int64(4));
    const int64_t rows = stmt.Int64(1);
    if (!IsVerifiedTwoViewGeometry(
            config,
            static_cast<size_t>(std::max<int64_t>(0, rows)),
            min_num_inliers)) {
      continue;
    }
    VerifiedTwoViewGeometry pair;
    pair.pair_id = static_cast<image_pair_t>(stmt.Int64(0));
    const ImagePair ids = PairIdToImagePair(pair.pair_id);
    pair.image_id1 = ids.first;
    pair.image_id2 = ids.second;
    pair.config = config;
    pair.inliers = ReadMatrixBlob<decltype(pair.inliers)>(
        stmt, 1, "two_view_geometries", static_cast<int64_t>(pair.pair_id));
    pair.F = ReadMatrix3Blob(stmt, 5);
    pair.E = ReadMatrix3Blob(stmt, 6);
    pair.H = ReadMatrix3Blob(stmt, 7);
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

bool TwoViewGeometryStore::HasHiddenPairsTable() const {
  SqliteStatement stmt(Handle(),
                       Path(),
                       "SELECT COUNT(*) FROM sqlite_master WHERE type = "
                       "'table' AND name = ?");
  stmt.BindText(1, kHiddenPairsTable);
  return stmt.Step() && stmt.Int64(0) > 0;
}

std::vector<std::string> TwoViewGeometryStore::TwoViewGeometryColumns() const {
  SqliteStatement stmt(
      Handle(), Path(), "PRAGMA table_info(two_view_geometries)");
  std::vector<std::string> columns;
  while (stmt.Step()) columns.push_back(stmt.Text(1));
  return columns;
}

std::vector<HiddenTwoViewGeometry> TwoViewGeometryStore::ReadHiddenPairs()
    const {
  std::vector<HiddenTwoViewGeometry> pairs;
  if (!HasHiddenPairsTable()) return pairs;
  SqliteStatement stmt(Handle(),
                       Path(),
                       (std::string("SELECT pair_id, gcn_reason, gcn_score, "
                                    "rows FROM ") +
                        kHiddenPairsTable + " ORDER BY pair_id")
                           .c_str());
  while (stmt.Step()) {
    HiddenTwoViewGeometry pair;
    pair.pair_id = static_cast<image_pair_t>(stmt.Int64(0));
    pair.reason = stmt.Text(1);
    pair.score = stmt.Double(2);
    pair.num_inliers = static_cast<size_t>(std::max<int64_t>(0, stmt.Int64(3)));
    pairs.push_back(pair);
  }
  return pairs;
}

void TwoViewGeometryStore::HidePairs(
    const std::vector<HiddenTwoViewGeometry>& pairs) {
  if (!writable_) ThrowError("database ", Path(), " was opened read-only");
  if (pairs.empty()) return;
  const std::vector<std::string> columns = TwoViewGeometryColumns();
  const std::string column_list = StringJoin(columns, ", ");
  Transaction transaction(Handle(), Path());
  // The side table holds two_view_geometries' columns as they are, plus why.
  Run(Handle(),
      Path(),
      std::string("CREATE TABLE IF NOT EXISTS ") + kHiddenPairsTable +
          " AS SELECT " + column_list +
          ", '' AS gcn_reason, 0.0 AS gcn_score FROM two_view_geometries "
          "WHERE 0");
  SqliteStatement copy(
      Handle(),
      Path(),
      (std::string("INSERT INTO ") + kHiddenPairsTable + " (" + column_list +
       ", gcn_reason, gcn_score) SELECT " + column_list +
       ", ?, ? FROM two_view_geometries WHERE pair_id = ? AND pair_id NOT IN "
       "(SELECT pair_id FROM " +
       kHiddenPairsTable + ")")
          .c_str());
  SqliteStatement blank(Handle(),
                        Path(),
                        "UPDATE two_view_geometries SET rows = 0, cols = 2, "
                        "data = NULL, config = 0 WHERE pair_id = ?");
  for (const HiddenTwoViewGeometry& pair : pairs) {
    copy.Reset();
    copy.BindText(1, pair.reason);
    copy.BindDouble(2, pair.score);
    copy.BindInt64(3, static_cast<int64_t>(pair.pair_id));
    copy.Execute();
    if (sqlite3_changes(Handle()) == 0) continue;
    blank.Reset();
    blank.BindInt64(1, static_cast<int64_t>(pair.pair_id));
    blank.Execute();
  }
  transaction.Commit();
}

size_t TwoViewGeometryStore::RestoreHiddenPairs() {
  if (!writable_) ThrowError("database ", Path(), " was opened read-only");
  if (!HasHiddenPairsTable()) return 0;
  const size_t count = SqliteQueryCount(
      Handle(),
      Path(),
      (std::string("SELECT COUNT(*) FROM ") + kHiddenPairsTable).c_str());
  const std::string column_list = StringJoin(TwoViewGeometryColumns(), ", ");
  Transaction transaction(Handle(), Path());
  Run(Handle(),
      Path(),
      std::string("INSERT OR REPLACE INTO two_view_geometries (") +
          column_list + ") SELECT " + column_list + " FROM " +
          kHiddenPairsTable);
  Run(Handle(), Path(), std::string("DROP TABLE ") + kHiddenPairsTable);
  transaction.Commit();
  return count;
}

}  // namespace colmap_gcn
