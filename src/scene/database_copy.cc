#include "scene/database_copy.h"

#include <fcntl.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "scene/database.h"
#include "util/error.h"
#include "util/logging.h"

namespace colmap_gcn {
namespace {

// Waiting this long for another connection's lock before giving up keeps a
// briefly busy database usable without hanging on one that stays busy.
const int kBusyTimeoutMs = 5000;

class Connection {
 public:
  Connection(const std::string& path, const int flags) : path_(path) {
    if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
      const std::string why =
          db_ != nullptr ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      ThrowError("cannot open database ", path, ": ", why);
    }
    sqlite3_busy_timeout(db_, kBusyTimeoutMs);
  }
  ~Connection() { sqlite3_close(db_); }
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  sqlite3* Get() const { return db_; }
  std::string Error() const { return sqlite3_errmsg(db_); }

  // The first column of the first row of sql, "" for no row.
  std::string QueryText(const char* sql) const {
    sqlite3_stmt* stmt = nullptr;
    if (sqlite3_prepare_v2(db_, sql, -1, &stmt, nullptr) != SQLITE_OK) {
      ThrowError("database ", path_, ": ", sql, ": ", Error());
    }
    std::string text;
    const int rc = sqlite3_step(stmt);
    if (rc == SQLITE_ROW) {
      const unsigned char* value = sqlite3_column_text(stmt, 0);
      if (value != nullptr) text = reinterpret_cast<const char*>(value);
    } else if (rc != SQLITE_DONE) {
      const std::string why = Error();
      sqlite3_finalize(stmt);
      ThrowError("database ", path_, ": ", sql, ": ", why);
    }
    sqlite3_finalize(stmt);
    return text;
  }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

}  // namespace

void RemoveDatabaseFiles(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
  for (const char* suffix : kDatabaseSideFileSuffixes) {
    std::filesystem::remove(path + suffix, ec);
  }
}

void CopyDatabase(const std::string& source_path,
                  const std::string& target_path) {
  struct stat source_info;
  if (stat(source_path.c_str(), &source_info) != 0) {
    ThrowError("cannot copy ", source_path, ": ", std::strerror(errno));
  }
  RemoveDatabaseFiles(target_path);
  try {
    const Connection source(source_path, SQLITE_OPEN_READONLY);
    const Connection target(target_path,
                            SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
    sqlite3_backup* backup =
        sqlite3_backup_init(target.Get(), "main", source.Get(), "main");
    if (backup == nullptr) {
      ThrowError("cannot copy ",
                 source_path,
                 " to ",
                 target_path,
                 ": ",
                 target.Error());
    }
    int rc = SQLITE_OK;
    do {
      rc = sqlite3_backup_step(backup, -1);
      if (rc == SQLITE_BUSY || rc == SQLITE_LOCKED) sqlite3_sleep(50);
    } while (rc == SQLITE_OK || rc == SQLITE_BUSY || rc == SQLITE_LOCKED);
    sqlite3_backup_finish(backup);
    if (rc != SQLITE_DONE) {
      ThrowError("cannot copy ",
                 source_path,
                 " to ",
                 target_path,
                 ": ",
                 sqlite3_errstr(rc));
    }
  } catch (...) {
    RemoveDatabaseFiles(target_path);
    throw;
  }
  chmod(target_path.c_str(), source_info.st_mode & 07777);
}

void CheckpointDatabase(const std::string& path) {
  const Connection db(path, SQLITE_OPEN_READWRITE);
  // Not in WAL mode: nothing lives outside the main file once open.
  if (db.QueryText("PRAGMA journal_mode;") != "wal") return;
  int log_frames = 0;
  int checkpointed_frames = 0;
  const int rc = sqlite3_wal_checkpoint_v2(db.Get(),
                                           nullptr,
                                           SQLITE_CHECKPOINT_TRUNCATE,
                                           &log_frames,
                                           &checkpointed_frames);
  if (rc == SQLITE_BUSY || rc == SQLITE_LOCKED) {
    ThrowError(path,
               " is in use by another program (its write-ahead log ",
               path,
               "-wal could not be folded in); close it and run again");
  }
  if (rc != SQLITE_OK) {
    ThrowError("cannot checkpoint ", path, ": ", db.Error());
  }
}

namespace {

// Writable as SQLite's rollback needs it: the file is rewritten and the
// journal beside it deleted. A missing write bit counts even for root, who
// passes access() regardless, so that a file made read-only stays unchanged.
bool IsWritableWithFolder(const std::string& path) {
  const std::string parent = std::filesystem::path(path).parent_path().string();
  const std::string dir = parent.empty() ? "." : parent;
  struct stat info;
  struct stat dir_info;
  return stat(path.c_str(), &info) == 0 && (info.st_mode & 0222) != 0 &&
         access(path.c_str(), W_OK) == 0 && stat(dir.c_str(), &dir_info) == 0 &&
         (dir_info.st_mode & 0222) != 0 &&
         access(dir.c_str(), W_OK | X_OK) == 0;
}

// Whether a read-only connection can read path, or SQLite refuses because a
// hot journal must be rolled back first. Other failures are left to the
// Database that opens path next, which names them.
bool NeedsRollback(const std::string& path) {
  sqlite3* db = nullptr;
  bool needs_rollback = false;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) ==
      SQLITE_OK) {
    sqlite3_busy_timeout(db, kBusyTimeoutMs);
    sqlite3_stmt* stmt = nullptr;
    if (sqlite3_prepare_v2(
            db, "SELECT count(*) FROM sqlite_master;", -1, &stmt, nullptr) ==
        SQLITE_OK) {
      sqlite3_step(stmt);
    }
    needs_rollback = sqlite3_extended_errcode(db) == SQLITE_READONLY_ROLLBACK;
    sqlite3_finalize(stmt);
  }
  sqlite3_close(db);
  return needs_rollback;
}

}  // namespace

std::string HotJournalMessage(const std::string& path) {
  return path +
         "-journal is the rollback journal of a transaction a crashed "
         "program left unfinished; SQLite must roll it back before " +
         path + " can be read: make " + path +
         " and its folder writable and run again, or open it once with "
         "`sqlite3 " +
         path + " 'PRAGMA integrity_check;'` as its owner";
}

void RecoverHotJournal(const std::string& path) {
  // SQLite keeps the journal beside the real file.
  std::error_code ec;
  const std::filesystem::path real = std::filesystem::canonical(path, ec);
  if (ec) return;
  const std::string db_path = real.string();
  struct stat journal;
  if (stat((db_path + "-journal").c_str(), &journal) != 0 ||
      journal.st_size == 0 || !NeedsRollback(db_path)) {
    return;
  }
  if (!IsWritableWithFolder(db_path)) ThrowError(HotJournalMessage(path));
  {
    const Connection db(db_path, SQLITE_OPEN_READWRITE);
    db.QueryText("SELECT count(*) FROM sqlite_master;");
  }
  if (NeedsRollback(db_path)) ThrowError(HotJournalMessage(path));
  LOG(WARNING) << path
               << " had an unfinished transaction of a program that crashed "
                  "(its rollback journal "
               << path << "-journal); SQLite rolled it back";
}

std::string CheckDatabaseIntegrity(const std::string& path) {
  try {
    const Connection db(path, SQLITE_OPEN_READWRITE);
    const std::string result = db.QueryText("PRAGMA quick_check;");
    return result == "ok" ? "" : result;
  } catch (const Error& error) {
    return error.what();
  }
}

void SyncFile(const std::string& path) {
  const int fd = open(path.c_str(), O_RDONLY);
  if (fd < 0 || fsync(fd) != 0) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) close(fd);
    ThrowError("cannot flush ", path, " to disk: ", why);
  }
  close(fd);
}

namespace {

void Exec(sqlite3* db, const std::string& sql) {
  char* message = nullptr;
  if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string why = message != nullptr ? message : "unknown error";
    sqlite3_free(message);
    ThrowError("merging databases failed: ", why);
  }
}

// SQL appending src.<table>'s rows to main.<table> under the merged pair
// ids. Both image ids move by the same offset o, so pair_id = id1 * K + id2
// (K = 2^31 - 1) moves by o * (K + 1); the blobs index keypoints, which
// keep their order.
std::string ShiftedPairRows(const std::string& table) {
  return "CREATE TEMP TABLE shifted AS SELECT * FROM src." + table +
         ";"
         "UPDATE shifted SET pair_id = pair_id + (SELECT img FROM offsets)"
         " * 2147483648;"
         "INSERT INTO main." +
         table + " SELECT * FROM shifted; DROP TABLE shifted;";
}

std::string SqlQuote(const std::string& str) {
  std::string quoted = "'";
  for (const char c : str) {
    quoted += c;
    if (c == '\'') quoted += '\'';
  }
  return quoted + "'";
}

}  // namespace

void MergeDatabases(const std::vector<std::string>& database_paths,
                    const std::string& merged_path,
                    const std::vector<std::string>& name_prefixes,
                    bool keep_matches) {
  if (database_paths.empty()) ThrowError("no database to merge");
  if (!name_prefixes.empty() && name_prefixes.size() != database_paths.size()) {
    ThrowError("merging ",
               database_paths.size(),
               " databases needs as many name prefixes (got ",
               name_prefixes.size(),
               ")");
  }
  std::vector<std::string> prefixes = name_prefixes;
  for (size_t i = prefixes.size(); i < database_paths.size(); ++i) {
    prefixes.push_back(std::to_string(i) + "/");
  }
  for (const std::string& path : database_paths) {
    const Database database(path);  // validates
    if (database.Schema() != DatabaseSchema::kColmap38) {
      ThrowError("cannot merge ",
                 path,
                 ": only COLMAP 3.8 databases can be merged for "
                 "vocab_tree_builder");
    }
  }
  CopyDatabase(database_paths[0], merged_path);
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(
          merged_path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) !=
      SQLITE_OK) {
    sqlite3_close(db);
    ThrowError("cannot open ", merged_path);
  }
  try {
    Exec(db, "PRAGMA journal_mode=DELETE;");
    if (!keep_matches) {
      Exec(db, "DELETE FROM matches; DELETE FROM two_view_geometries;");
    }
    Exec(db, "UPDATE images SET name = " + SqlQuote(prefixes[0]) + " || name;");
    for (size_t i = 1; i < database_paths.size(); ++i) {
      Exec(db, "ATTACH DATABASE " + SqlQuote(database_paths[i]) + " AS src;");
      Exec(db,
           "BEGIN;"
           "CREATE TEMP TABLE offsets AS SELECT"
           " (SELECT IFNULL(MAX(camera_id), 0) FROM main.cameras) AS cam,"
           " (SELECT IFNULL(MAX(image_id), 0) FROM main.images) AS img;"
           "INSERT INTO main.cameras SELECT camera_id + (SELECT cam FROM"
           " offsets), model, width, height, params, prior_focal_length"
           " FROM src.cameras;"
           "INSERT INTO main.images SELECT"
           " image_id + (SELECT img FROM offsets), " +
               SqlQuote(prefixes[i]) +
               " || name, camera_id + (SELECT cam FROM offsets),"
               " prior_qw, prior_qx, prior_qy, prior_qz, prior_tx, prior_ty,"
               " prior_tz FROM src.images;"
               "INSERT INTO main.keypoints SELECT image_id + (SELECT img FROM"
               " offsets), rows, cols, data FROM src.keypoints;"
               "INSERT INTO main.descriptors SELECT image_id + (SELECT img"
               " FROM offsets), rows, cols, data FROM src.descriptors;" +
               (keep_matches ? ShiftedPairRows("matches") +
                                   ShiftedPairRows("two_view_geometries")
                             : std::string()) +
               "DROP TABLE offsets;"
               "COMMIT;");
      Exec(db, "DETACH DATABASE src;");
    }
  } catch (...) {
    sqlite3_close(db);
    throw;
  }
  sqlite3_close(db);
}

void RemoveEmptySqliteSideFiles(const std::string& path) {
  // SQLite keeps them beside the file a symbolic link points to.
  std::error_code ec;
  std::string real_path = std::filesystem::weakly_canonical(path, ec).string();
  if (ec || real_path.empty()) real_path = path;
  const std::string wal_path = real_path + "-wal";
  if (std::filesystem::is_regular_file(wal_path, ec) &&
      std::filesystem::file_size(wal_path, ec) == 0) {
    std::filesystem::remove(wal_path, ec);
  }
  if (!std::filesystem::exists(wal_path, ec)) {
    std::filesystem::remove(real_path + "-shm", ec);
  }
}

}  // namespace colmap_gcn
