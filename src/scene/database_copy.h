#pragma once

#include <string>
#include <vector>

namespace colmap_gcn {

// Whole-file operations on COLMAP's SQLite databases. They always go through
// SQLite, never through plain file copies: COLMAP opens its databases in WAL
// mode, so committed data can live in "<path>-wal" until a checkpoint, and a
// "-wal" file left beside the wrong main file is replayed onto it.

// The side files SQLite may keep beside a database: "-wal", "-shm",
// "-journal".
const char* const kDatabaseSideFileSuffixes[] = {"-wal", "-shm", "-journal"};

// Removes path and its side files (missing files are fine).
void RemoveDatabaseFiles(const std::string& path);

// Removes an empty "<path>-wal" (a reader of a WAL database leaves one: it
// holds nothing) and then a "<path>-shm" without its "-wal" (only an index
// of it), beside the file path resolves to. A "-wal" with content is never
// touched.
void RemoveEmptySqliteSideFiles(const std::string& path);

// A consistent snapshot of source (committed WAL content included) written to
// target with SQLite's online backup API. Whatever was at target, including
// stale side files of an earlier copy, is removed first. The copy gets the
// source's permission bits. Throws Error naming both paths on failure.
void CopyDatabase(const std::string& source_path,
                  const std::string& target_path);

// Folds the committed content of path's write-ahead log into the main file
// and truncates the log (read-write; a no-op for databases not in WAL mode).
// Throws Error when another program keeps the log busy.
void CheckpointDatabase(const std::string& path);

// Rolls back the hot journal a crashed writer left beside path: a non-empty
// "<path>-journal" of a database in rollback-journal mode (journal_mode
// DELETE, as hloc, pycolmap and older COLMAP write) that no connection holds.
// Until SQLite rolls it back, every read-only open fails with "attempt to
// write a readonly database". When the database and its folder are writable
// (a write permission bit is required even for root), the database is opened
// read-write once and read, which makes SQLite roll the journal back, and a
// warning is logged; otherwise throws Error saying what the journal is and
// how to recover. Does nothing when there is no such journal, or when SQLite
// reads the database without a rollback (the journal's writer is alive).
void RecoverHotJournal(const std::string& path);

// The one-line explanation of a hot journal that cannot be rolled back.
std::string HotJournalMessage(const std::string& path);

// SQLite's structural check (PRAGMA quick_check) on the database opened
// read-write, so that a write-ahead log of its own is replayed first.
// Returns "" when it is sound, else the first problem SQLite reports.
std::string CheckDatabaseIntegrity(const std::string& path);

// Flushes path's contents to disk (fsync), so a rename that publishes it
// survives a power loss; throws Error on failure.
void SyncFile(const std::string& path);

// One COLMAP 3.8 database at merged_path holding all cameras, images (with
// their pose priors), keypoints and descriptors of the inputs, ids offset
// past the previous inputs'; image names get the prefix name_prefixes[i]
// (empty: "<input index>/") so they stay unique. Matches and
// two_view_geometries are dropped, or with keep_matches kept under the new
// pair ids: each input's own pairs then look matched and every pair across
// inputs unmatched (a collection of scenes matched alone, for replaying a
// pairing on it without matching it). Throws Error on failure.
void MergeDatabases(const std::vector<std::string>& database_paths,
                    const std::string& merged_path,
                    const std::vector<std::string>& name_prefixes = {},
                    bool keep_matches = false);

}  // namespace colmap_gcn
