#include "util/file_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <mutex>

#include "util/error.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

struct HeldLock {
  int fd = -1;
  int count = 0;
  pid_t owner = 0;  // a forked child inherits the map, not the lock's use
};

std::mutex& HeldLocksMutex() {
  static std::mutex mutex;
  return mutex;
}

std::map<std::string, HeldLock>& HeldLocks() {
  static std::map<std::string, HeldLock> locks;
  return locks;
}

std::string ReadHolder(const int fd) {
  char buffer[64] = {0};
  const ssize_t n = pread(fd, buffer, sizeof(buffer) - 1, 0);
  return n > 0 ? StringTrim(std::string(buffer, n)) : "";
}

// Opens and locks path. The file may be unlinked by its previous holder
// between our open and flock; then the lock is on a dead inode, so retry
// until the locked file is the one at path.
int AcquireLock(const std::string& path, const std::string& what) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = open(path.c_str(), O_RDWR | O_CREAT, 0644);
    if (fd < 0) {
      ThrowError("cannot create the lock file ",
                 path,
                 " for ",
                 what,
                 ": ",
                 std::strerror(errno));
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string holder = ReadHolder(fd);
      close(fd);
      if (error == EWOULDBLOCK) {
        ThrowError("another gcn_matcher is using ",
                   what,
                   holder.empty() ? "" : " (pid " + holder + ")",
                   "; wait for it to finish (lock file ",
                   path,
                   ")");
      }
      ThrowError("cannot lock ", path, ": ", std::strerror(error));
    }
    struct stat locked, current;
    if (fstat(fd, &locked) == 0 && stat(path.c_str(), &current) == 0 &&
        locked.st_ino == current.st_ino && locked.st_dev == current.st_dev) {
      const std::string pid = std::to_string(getpid()) + "\n";
      if (ftruncate(fd, 0) != 0 || pwrite(fd, pid.data(), pid.size(), 0) !=
                                       static_cast<ssize_t>(pid.size())) {
        // The pid is only informative; the lock itself is held.
      }
      return fd;
    }
    close(fd);
  }
  ThrowError("cannot lock ", path, ": it keeps being replaced");
}

}  // namespace

ScopedFileLock::ScopedFileLock(const std::string& lock_path,
                               const std::string& what)
    : path_(lock_path) {
  std::lock_guard<std::mutex> guard(HeldLocksMutex());
  HeldLock& held = HeldLocks()[path_];
  if (held.count == 0 || held.owner != getpid()) {
    try {
      held.fd = AcquireLock(path_, what);
    } catch (...) {
      HeldLocks().erase(path_);
      throw;
    }
    held.count = 0;
    held.owner = getpid();
  }
  ++held.count;
}

ScopedFileLock::~ScopedFileLock() {
  std::lock_guard<std::mutex> guard(HeldLocksMutex());
  auto it = HeldLocks().find(path_);
  if (it == HeldLocks().end() || --it->second.count > 0) return;
  // Unlink while still holding the lock, so no waiter locks a removed file
  // believing it is current (AcquireLock re-checks the inode).
  unlink(path_.c_str());
  close(it->second.fd);
  HeldLocks().erase(it);
}

}  // namespace colmap_gcn
