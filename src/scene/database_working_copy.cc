#include "scene/database_working_copy.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "scene/database.h"
#include "scene/database_copy.h"
#include "util/error.h"
#include "util/file.h"
#include "util/interrupt.h"
#include "util/logging.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

namespace fs = std::filesystem;

const char* const kCopySuffix = ".gcn-partial";
const char* const kSourceSuffix = ".gcn-partial.source";

// Size and modification time of a file, "-" when it does not exist or is
// empty (read-only connections leave empty side files behind).
std::string FileState(const std::string& path) {
  struct stat info;
  if (stat(path.c_str(), &info) != 0 || info.st_size == 0) return "-";
  return std::to_string(info.st_size) + "@" +
         std::to_string(info.st_mtim.tv_sec) + "." +
         std::to_string(info.st_mtim.tv_nsec);
}

// The database's state as other programs could change it: the main file and
// its side files (a writer in WAL mode only touches "-wal").
std::string DatabaseFingerprint(const std::string& path) {
  return FileState(path) + " " + FileState(path + "-wal") + " " +
         FileState(path + "-journal");
}

void SyncDirectoryOf(const std::string& path) {
  const std::string dir = fs::path(path).parent_path().string();
  const int fd = open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd >= 0) {
    fsync(fd);
    close(fd);
  }
}

void RemoveIfEmpty(const std::string& path) {
  struct stat info;
  if (stat(path.c_str(), &info) == 0 && info.st_size == 0) {
    unlink(path.c_str());
  }
}

// Side files left after SQLite folded everything into the main file: an
// empty log, an index of no log, an empty rollback journal.
void RemoveEmptySideFiles(const std::string& path) {
  RemoveIfEmpty(path + "-wal");
  RemoveIfEmpty(path + "-journal");
  if (!ExistsFile(path + "-wal")) unlink((path + "-shm").c_str());
}

}  // namespace

std::string ResolveDatabasePath(const std::string& database_path) {
  std::error_code ec;
  const fs::path real = fs::canonical(database_path, ec);
  if (ec) {
    ThrowError("database ", database_path, " does not exist");
  }
  if (!fs::is_regular_file(real, ec)) {
    ThrowError("database ", database_path, " is not a file");
  }
  return real.string();
}

void CheckDatabaseWritable(const std::string& database_path) {
  struct stat info;
  if (stat(database_path.c_str(), &info) != 0) {
    ThrowError("database ", database_path, " does not exist");
  }
  const bool no_write_bit = (info.st_mode & 0222) == 0;
  if (no_write_bit || access(database_path.c_str(), W_OK) != 0) {
    const int access_errno = no_write_bit ? 0 : errno;
    char mode[8];
    std::snprintf(mode, sizeof(mode), "%04o", info.st_mode & 07777);
    // chmod u+w only helps its owner when the owner's bit is what is missing.
    const uid_t uid = geteuid();
    if (info.st_uid == uid && (info.st_mode & 0200) == 0) {
      ThrowError("database ",
                 database_path,
                 " is read-only (mode ",
                 mode,
                 "); matching writes into it, so make it writable "
                 "(chmod u+w) or match a copy");
    }
    if (access_errno == EROFS) {
      ThrowError("database ",
                 database_path,
                 " is on a read-only file system; matching writes into it, "
                 "so match a copy on a writable one");
    }
    ThrowError("database ",
               database_path,
               " (mode ",
               mode,
               ") is owned by uid ",
               info.st_uid,
               ", not writable by uid ",
               uid,
               "; matching writes into it, so run as a user who may write "
               "it or match a copy");
  }
  const std::string dir = fs::path(database_path).parent_path().string();
  struct stat dir_info;
  if (stat(dir.c_str(), &dir_info) != 0 || (dir_info.st_mode & 0222) == 0 ||
      access(dir.c_str(), W_OK | X_OK) != 0) {
    ThrowError("the folder ",
               dir,
               " of database ",
               database_path,
               " is read-only; matching needs to write a copy of the "
               "database beside it");
  }
}

std::string DatabaseLockPath(const std::string& database_path) {
  return database_path + ".gcn-lock";
}

DatabaseWorkingCopy::DatabaseWorkingCopy(const std::string& database_path)
    : database_path_(ResolveDatabasePath(database_path)),
      copy_path_(database_path_ + kCopySuffix) {
  CheckDatabaseWritable(database_path_);
  CheckpointDatabase(database_path_);
  fingerprint_ = DatabaseFingerprint(database_path_);
  const std::string source_path = database_path_ + kSourceSuffix;

  if (ExistsFile(copy_path_) && ExistsFile(source_path) &&
      StringTrim(ReadTextFile(source_path)) == fingerprint_) {
    const std::string problem = CheckDatabaseIntegrity(copy_path_);
    if (problem.empty()) {
      resumed_ = true;
      return;
    }
    LOG(WARNING) << "discarding the interrupted matching in " << copy_path_
                 << ": SQLite reports it damaged (" << problem
                 << "); starting over from " << database_path_;
  }
  // The record goes first so that a copy interrupted half-way is never
  // taken for a complete one.
  std::error_code ec;
  fs::remove(source_path, ec);
  CopyDatabase(database_path_, copy_path_);
  WriteFileAtomically(source_path, fingerprint_ + "\n");
}

DatabaseWorkingCopy::~DatabaseWorkingCopy() {
  if (committed_ || resumed_ || written_) return;
  RemoveDatabaseFiles(copy_path_);
  std::error_code ec;
  fs::remove(database_path_ + kSourceSuffix, ec);
}

void DatabaseWorkingCopy::Commit() {
  const std::string source_path = database_path_ + kSourceSuffix;
  CheckpointDatabase(copy_path_);
  const std::string problem = CheckDatabaseIntegrity(copy_path_);
  if (!problem.empty()) {
    RemoveDatabaseFiles(copy_path_);
    std::error_code ec;
    fs::remove(source_path, ec);
    ThrowError("the matched copy ",
               copy_path_,
               " failed SQLite's check (",
               problem,
               "); it was discarded and ",
               database_path_,
               " is unchanged: run again");
  }
  { const Database check(copy_path_); }
  if (DatabaseFingerprint(database_path_) != fingerprint_) {
    ThrowError(database_path_,
               " was changed by another program during matching, so it was "
               "not replaced; this run's matches are in ",
               copy_path_,
               " (the next run starts over from the changed database)");
  }
  RemoveEmptySideFiles(copy_path_);
  SyncFile(copy_path_);
  StopPointForTests("commit");
  std::error_code ec;
  fs::rename(copy_path_, database_path_, ec);
  if (ec) {
    ThrowError("cannot replace ",
               database_path_,
               " with ",
               copy_path_,
               ": ",
               ec.message());
  }
  committed_ = true;
  SyncDirectoryOf(database_path_);
  // The database's own log was folded in before the copy was made.
  RemoveEmptySideFiles(database_path_);
  fs::remove(source_path, ec);
}

}  // namespace colmap_gcn
