#pragma once

#include <cstdint>
#include <cstring>
#include <string>

#include <Eigen/Core>

#include "util/error.h"

struct sqlite3;
struct sqlite3_stmt;

namespace colmap_gcn {

struct DatabaseImage;

// The SQLite access Database (and the tests' DatabaseInspector) build on;
// only scene/ and test utilities include it.

// A prepared statement that finalizes itself and turns every sqlite failure
// into a one-line Error naming the database, so that callers never have to
// check return codes.
class SqliteStatement {
 public:
  SqliteStatement(sqlite3* db, const std::string& db_path, const char* sql);
  ~SqliteStatement();
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  void BindInt64(int index, int64_t value);
  void BindDouble(int index, double value);
  void BindText(int index, const std::string& value);
  void BindBlob(int index, const void* data, size_t num_bytes);

  // Returns true when a row is available, false when the statement is done.
  bool Step();
  void Execute();
  // Ready to bind and run again.
  void Reset();

  int64_t Int64(int col) const;
  double Double(int col) const;
  bool IsNull(int col) const;
  std::string Text(int col) const;
  // Blob pointer (may be null for NULL or empty blobs) and its size.
  const void* Blob(int col, size_t* num_bytes) const;

  const std::string& DbPath() const { return db_path_; }

 private:
  void Check(int rc, const char* action) const;
  [[noreturn]] void Fail(const char* action) const;

  sqlite3* db_;
  const std::string& db_path_;
  sqlite3_stmt* stmt_ = nullptr;
};

// Runs a query that returns a single integer (COUNT, SUM); NULL gives 0.
size_t SqliteQueryCount(sqlite3* db,
                        const std::string& db_path,
                        const char* sql);

// An image from a row that starts (image_id, name, camera_id).
DatabaseImage ReadImageRow(const SqliteStatement& stmt);

// Reads the (rows, cols, data) column triple starting at col into a matrix,
// as COLMAP stores keypoints, descriptors and matches. A NULL or empty blob
// with zero rows is an empty matrix; any size mismatch is corruption.
template <typename MatrixType>
MatrixType ReadMatrixBlob(const SqliteStatement& stmt,
                          const int col,
                          const char* table,
                          const int64_t key) {
  typedef typename MatrixType::Scalar Scalar;
  const int64_t rows = stmt.Int64(col);
  const int64_t cols = stmt.Int64(col + 1);
  size_t num_bytes = 0;
  const void* data = stmt.Blob(col + 2, &num_bytes);

  const bool fixed_cols = MatrixType::ColsAtCompileTime != Eigen::Dynamic;
  if (rows < 0 || cols < 0 ||
      (fixed_cols && rows > 0 && cols != MatrixType::ColsAtCompileTime)) {
    ThrowError("database ",
               stmt.DbPath(),
               ": invalid shape ",
               rows,
               "x",
               cols,
               " in ",
               table,
               " for id ",
               key);
  }
  const size_t expected_bytes =
      static_cast<size_t>(rows) * static_cast<size_t>(cols) * sizeof(Scalar);
  if (num_bytes != expected_bytes) {
    ThrowError("database ",
               stmt.DbPath(),
               ": blob of ",
               num_bytes,
               " bytes in ",
               table,
               " for id ",
               key,
               " does not match its shape ",
               rows,
               "x",
               cols);
  }

  const int64_t matrix_cols =
      fixed_cols ? static_cast<int64_t>(MatrixType::ColsAtCompileTime) : cols;
  MatrixType matrix(rows, matrix_cols);
  if (expected_bytes > 0) {
    std::memcpy(matrix.data(), data, expected_bytes);
  }
  return matrix;
}

}  // namespace colmap_gcn
