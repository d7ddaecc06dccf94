#pragma once

#include <string>

namespace colmap_gcn {

// The real file behind a database path (symlinks resolved), so that copies,
// locks and the final rename act on the user's actual database; throws Error
// when it does not exist.
std::string ResolveDatabasePath(const std::string& database_path);

// Throws Error unless the database file and its folder can be written: the
// file must have a write permission bit and be writable by this user, the
// folder must accept the copy that later replaces the file.
void CheckDatabaseWritable(const std::string& database_path);

// The lock file that keeps two gcn_matcher runs off one database.
std::string DatabaseLockPath(const std::string& database_path);

// The copy of a user's database that COLMAP writes into, so that the
// database itself only ever changes by one atomic rename of a verified file.
//
// The copy ("<database>.gcn-partial", beside the real file) is made through
// SQLite after folding the database's write-ahead log in, so committed data
// that COLMAP left in "<database>-wal" is never lost. "<copy>.source" records
// the database's state; while that state is unchanged, the next run resumes
// the copy (keeping everything COLMAP committed into it), unless SQLite finds
// it damaged, in which case it is discarded and made anew. Commit() verifies
// the copy, flushes it to disk and renames it over the database, but only if
// no other program changed the database meanwhile. A new copy that nothing
// was written into (MarkWritten) holds nothing worth resuming: it is removed
// when the object goes without a Commit().
class DatabaseWorkingCopy {
 public:
  explicit DatabaseWorkingCopy(const std::string& database_path);
  ~DatabaseWorkingCopy();
  DatabaseWorkingCopy(const DatabaseWorkingCopy&) = delete;
  DatabaseWorkingCopy& operator=(const DatabaseWorkingCopy&) = delete;

  // The copy COLMAP should write into.
  const std::string& Path() const { return copy_path_; }
  // The real database file (symlinks resolved).
  const std::string& DatabasePath() const { return database_path_; }
  // True when an interrupted earlier run's copy is continued.
  bool Resumed() const { return resumed_; }

  // Call before another program (COLMAP) writes into the copy: from then on
  // the copy is kept for the next run to resume.
  void MarkWritten() { written_ = true; }

  // Replaces the database with the verified copy; throws Error (leaving the
  // database as it is) when the copy is damaged or the database changed.
  void Commit();

 private:
  std::string database_path_;
  std::string copy_path_;
  std::string fingerprint_;
  bool resumed_ = false;
  bool written_ = false;
  bool committed_ = false;
};

}  // namespace colmap_gcn
