#pragma once

#include <string>

namespace colmap_gcn {

// An exclusive advisory lock (flock) on a lock file, held for the lifetime of
// the object. Acquiring never waits: when another process holds the lock the
// constructor throws Error naming the holder's pid. The lock is re-entrant
// within a process (a second ScopedFileLock on the same path shares the
// first), and child processes started while it is held inherit it, so an
// orphaned COLMAP child still writing keeps other runs out. The lock file is
// removed when the last holder in this process releases it.
class ScopedFileLock {
 public:
  // what: how the holder is described in the error ("another gcn_matcher is
  // using <what>").
  ScopedFileLock(const std::string& lock_path, const std::string& what);
  ~ScopedFileLock();
  ScopedFileLock(const ScopedFileLock&) = delete;
  ScopedFileLock& operator=(const ScopedFileLock&) = delete;

  const std::string& Path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace colmap_gcn
