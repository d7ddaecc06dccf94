#include "scene/database_inspector.h"

#include <sqlite3.h>

#include <algorithm>
#include <cstring>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "scene/sqlite_statement.h"
#include "util/error.h"

namespace colmap_gcn {
namespace test {
namespace {

// Reads a fixed-size float64 blob (F, E, H as 9 row-major values, qvec,
// tvec). A NULL/empty blob keeps the default; other sizes are corruption.
template <int N>
void ReadDoubleBlob(const SqliteStatement& stmt,
                    const int col,
                    const char* name,
                    const int64_t pair_id,
                    double* values) {
  size_t num_bytes = 0;
  const void* data = stmt.Blob(col, &num_bytes);
  if (num_bytes == 0) return;
  if (num_bytes != N * sizeof(double)) {
    ThrowError("database ",
               stmt.DbPath(),
               ": ",
               name,
               " blob of two_view_geometries pair_id ",
               pair_id,
               " has ",
               num_bytes,
               " bytes, expected ",
               N * sizeof(double));
  }
  std::memcpy(values, data, num_bytes);
}

// COLMAP writes F, E, H as row-major 3x3.
Eigen::Matrix3d ReadRowMajorMatrix3d(const SqliteStatement& stmt,
                                     const int col,
                                     const char* name,
                                     const int64_t pair_id) {
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> matrix =
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor>::Zero();
  ReadDoubleBlob<9>(stmt, col, name, pair_id, matrix.data());
  return matrix;
}

// Expresses a two-view geometry estimated for (image1, image2) as the one for
// (image2, image1), as COLMAP's TwoViewGeometry::Invert does.
void InvertTwoViewGeometry(TwoViewGeometry* geometry) {
  geometry->F.transposeInPlace();
  geometry->E.transposeInPlace();
  // An unset (zero) homography has no inverse; keep it zero rather than
  // filling it with infinities.
  if (geometry->H.determinant() != 0.0) {
    geometry->H = geometry->H.inverse().eval();
  }
  if (geometry->qvec.norm() > 0.0) {
    const Eigen::Vector4d q = geometry->qvec.normalized();
    const Eigen::Quaterniond q_inv(q(0), -q(1), -q(2), -q(3));
    geometry->tvec = -(q_inv.toRotationMatrix() * geometry->tvec);
    geometry->qvec = Eigen::Vector4d(q(0), -q(1), -q(2), -q(3));
  }
  geometry->inlier_matches.col(0).swap(geometry->inlier_matches.col(1));
}

}  // namespace

size_t DatabaseInspector::NumCameras() const {
  return SqliteQueryCount(Handle(), Path(), "SELECT COUNT(*) FROM cameras");
}

size_t DatabaseInspector::NumKeypoints() const {
  return SqliteQueryCount(Handle(), Path(), "SELECT SUM(rows) FROM keypoints");
}

size_t DatabaseInspector::NumMatchedPairs() const {
  return SqliteQueryCount(Handle(), Path(), "SELECT COUNT(*) FROM matches");
}

size_t DatabaseInspector::NumTwoViewGeometries() const {
  return SqliteQueryCount(
      Handle(), Path(), "SELECT COUNT(*) FROM two_view_geometries");
}

bool DatabaseInspector::ExistsImageWithName(const std::string& name) const {
  SqliteStatement stmt(Handle(), Path(), "SELECT 1 FROM images WHERE name = ?");
  stmt.BindText(1, name);
  return stmt.Step();
}

DatabaseImage DatabaseInspector::ReadImageWithName(
    const std::string& name) const {
  SqliteStatement stmt(
      Handle(),
      Path(),
      "SELECT image_id, name, camera_id FROM images WHERE name = ?");
  stmt.BindText(1, name);
  if (!stmt.Step()) {
    ThrowError("database ", Path(), " has no image named '", name, "'");
  }
  return ReadImageRow(stmt);
}

FeatureKeypoints DatabaseInspector::ReadKeypoints(
    const image_t image_id) const {
  SqliteStatement stmt(
      Handle(),
      Path(),
      "SELECT rows, cols, data FROM keypoints WHERE image_id = ?");
  stmt.BindInt64(1, image_id);
  if (!stmt.Step()) {
    return FeatureKeypoints(0, 2);
  }
  FeatureKeypoints keypoints =
      ReadMatrixBlob<FeatureKeypoints>(stmt, 0, "keypoints", image_id);
  const Eigen::Index cols = keypoints.cols();
  if (keypoints.rows() > 0 && cols != 2 && cols != 4 && cols != 6) {
    ThrowError("database ",
               Path(),
               ": keypoints of image ",
               image_id,
               " have ",
               cols,
               " columns, expected 2, 4 or 6");
  }
  return keypoints;
}

size_t DatabaseInspector::NumKeypointsForImage(const image_t image_id) const {
  SqliteStatement stmt(
      Handle(), Path(), "SELECT rows FROM keypoints WHERE image_id = ?");
  stmt.BindInt64(1, image_id);
  return stmt.Step() ? static_cast<size_t>(stmt.Int64(0)) : 0;
}

FeatureMatches DatabaseInspector::ReadMatches(const image_t image_id1,
                                              const image_t image_id2) const {
  const int64_t pair_id =
      static_cast<int64_t>(ImagePairToPairId(image_id1, image_id2));
  SqliteStatement stmt(
      Handle(),
      Path(),
      "SELECT rows, cols, data FROM matches WHERE pair_id = ?");
  stmt.BindInt64(1, pair_id);
  if (!stmt.Step()) {
    return FeatureMatches(0, 2);
  }
  FeatureMatches matches =
      ReadMatrixBlob<FeatureMatches>(stmt, 0, "matches", pair_id);
  if (SwapImagePair(image_id1, image_id2)) {
    matches.col(0).swap(matches.col(1));
  }
  return matches;
}

std::vector<image_pair_t> DatabaseInspector::ReadMatchedPairIds() const {
  SqliteStatement stmt(
      Handle(), Path(), "SELECT pair_id FROM matches ORDER BY pair_id");
  std::vector<image_pair_t> pair_ids;
  while (stmt.Step()) {
    pair_ids.push_back(static_cast<image_pair_t>(stmt.Int64(0)));
  }
  return pair_ids;
}

bool DatabaseInspector::ExistsMatches(const image_t image_id1,
                                      const image_t image_id2) const {
  SqliteStatement stmt(
      Handle(), Path(), "SELECT 1 FROM matches WHERE pair_id = ?");
  stmt.BindInt64(1,
                 static_cast<int64_t>(ImagePairToPairId(image_id1, image_id2)));
  return stmt.Step();
}

TwoViewGeometry DatabaseInspector::ReadTwoViewGeometry(
    const image_t image_id1, const image_t image_id2) const {
  const int64_t key =
      static_cast<int64_t>(ImagePairToPairId(image_id1, image_id2));
  SqliteStatement stmt(Handle(),
                       Path(),
                       "SELECT rows, cols, data, config, F, E, H, qvec, tvec "
                       "FROM two_view_geometries WHERE pair_id = ?");
  stmt.BindInt64(1, key);
  TwoViewGeometry geometry;
  if (!stmt.Step()) {
    geometry.inlier_matches = FeatureMatches(0, 2);
    return geometry;
  }
  geometry.inlier_matches =
      ReadMatrixBlob<FeatureMatches>(stmt, 0, "two_view_geometries", key);
  geometry.config = static_cast<int>(stmt.Int64(3));
  geometry.F = ReadRowMajorMatrix3d(stmt, 4, "F", key);
  geometry.E = ReadRowMajorMatrix3d(stmt, 5, "E", key);
  geometry.H = ReadRowMajorMatrix3d(stmt, 6, "H", key);
  ReadDoubleBlob<4>(stmt, 7, "qvec", key, geometry.qvec.data());
  ReadDoubleBlob<3>(stmt, 8, "tvec", key, geometry.tvec.data());
  if (SwapImagePair(image_id1, image_id2)) {
    InvertTwoViewGeometry(&geometry);
  }
  return geometry;
}

bool DatabaseInspector::ExistsTwoViewGeometry(const image_t image_id1,
                                              const image_t image_id2) const {
  SqliteStatement stmt(
      Handle(), Path(), "SELECT 1 FROM two_view_geometries WHERE pair_id = ?");
  stmt.BindInt64(1,
                 static_cast<int64_t>(ImagePairToPairId(image_id1, image_id2)));
  return stmt.Step();
}

}  // namespace test
}  // namespace colmap_gcn
