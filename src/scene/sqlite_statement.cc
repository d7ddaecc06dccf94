#include "scene/sqlite_statement.h"

#include <sqlite3.h>

#include <algorithm>

#include "scene/database.h"

namespace colmap_gcn {

SqliteStatement::SqliteStatement(sqlite3* db,
                                 const std::string& db_path,
                                 const char* sql)
    : db_(db), db_path_(db_path) {
  if (sqlite3_prepare_v2(db_, sql, -1, &stmt_, nullptr) != SQLITE_OK) {
    Fail("preparing");
  }
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(stmt_); }

void SqliteStatement::BindInt64(const int index, const int64_t value) {
  Check(sqlite3_bind_int64(stmt_, index, value), "binding");
}

void SqliteStatement::BindDouble(const int index, const double value) {
  Check(sqlite3_bind_double(stmt_, index, value), "binding");
}

void SqliteStatement::BindText(const int index, const std::string& value) {
  Check(sqlite3_bind_text(stmt_,
                          index,
                          value.data(),
                          static_cast<int>(value.size()),
                          SQLITE_TRANSIENT),
        "binding");
}

void SqliteStatement::BindBlob(const int index,
                               const void* data,
                               const size_t num_bytes) {
  Check(sqlite3_bind_blob(
            stmt_, index, data, static_cast<int>(num_bytes), SQLITE_TRANSIENT),
        "binding");
}

bool SqliteStatement::Step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  Fail("executing");
}

void SqliteStatement::Execute() {
  while (Step()) {
  }
}

void SqliteStatement::Reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

int64_t SqliteStatement::Int64(const int col) const {
  return sqlite3_column_int64(stmt_, col);
}

double SqliteStatement::Double(const int col) const {
  return sqlite3_column_double(stmt_, col);
}

bool SqliteStatement::IsNull(const int col) const {
  return sqlite3_column_type(stmt_, col) == SQLITE_NULL;
}

std::string SqliteStatement::Text(const int col) const {
  const unsigned char* text = sqlite3_column_text(stmt_, col);
  const int num_bytes = sqlite3_column_bytes(stmt_, col);
  return text == nullptr
             ? std::string()
             : std::string(reinterpret_cast<const char*>(text), num_bytes);
}

const void* SqliteStatement::Blob(const int col, size_t* num_bytes) const {
  const void* data = sqlite3_column_blob(stmt_, col);
  *num_bytes = static_cast<size_t>(sqlite3_column_bytes(stmt_, col));
  return data;
}

void SqliteStatement::Check(const int rc, const char* action) const {
  if (rc != SQLITE_OK) Fail(action);
}

void SqliteStatement::Fail(const char* action) const {
  ThrowError("database ",
             db_path_,
             ": sqlite error while ",
             action,
             " '",
             stmt_ != nullptr ? sqlite3_sql(stmt_) : "statement",
             "': ",
             sqlite3_errmsg(db_));
}

DatabaseImage ReadImageRow(const SqliteStatement& stmt) {
  DatabaseImage image;
  image.image_id = static_cast<image_t>(stmt.Int64(0));
  image.name = stmt.Text(1);
  image.camera_id = static_cast<camera_t>(stmt.Int64(2));
  return image;
}

size_t SqliteQueryCount(sqlite3* db,
                        const std::string& db_path,
                        const char* sql) {
  SqliteStatement stmt(db, db_path, sql);
  if (!stmt.Step() || stmt.IsNull(0)) return 0;
  return static_cast<size_t>(std::max<int64_t>(0, stmt.Int64(0)));
}

}  // namespace colmap_gcn
