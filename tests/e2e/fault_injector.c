// An LD_PRELOAD library that makes writes fail as a full or broken disk
// does, for one program and one set of files, without root or a small file
// system. Configured by the environment:
//
//   COLMAP_GCN_FAULT_EXE          act only in a process whose executable
//                                 (realpath of /proc/self/exe) is this file;
//                                 unset: every process
//   COLMAP_GCN_FAULT_PATH         act only on files whose path (readlink of
//                                 /proc/self/fd/N) contains this; unset or
//                                 empty: the injector is off
//   COLMAP_GCN_FAULT_AFTER_BYTES  bytes let through to those files first,
//                                 counted across the process (default 0)
//   COLMAP_GCN_FAULT_COUNTER      a file that holds the count instead, so it
//                                 spans every process naming it (gcn_matcher
//                                 runs one COLMAP per block: a fault mid-way
//                                 through the run, not through each block)
//   COLMAP_GCN_FAULT_ERRNO        ENOSPC (default), EIO, EDQUOT or a number
//   COLMAP_GCN_FAULT_LOG          a file that gets one line per failed call
//
// A write that does not fit in what is left of the budget fails whole, as
// on a disk with that much free space: with ENOSPC a later, smaller write
// that still fits goes through. SQLite's "-shm" index is left out with
// ENOSPC: each connection sizes it with 1-byte writes at open, and on a real
// disk the space the previous COLMAP run's deleted "-wal" freed takes them,
// so a later run opens the database and fails at its commit with "database
// or disk is full" (issue 25's later blocks on a full tmpfs exited 0 the
// same way) instead of failing to open it. With EIO the device
// is broken for good: every later write fails, and so do fsync and
// fdatasync of those files, as after the kernel lost a page it could not
// write back.
//
// Only calls that go through the dynamic linker are seen: SQLite's pwrite64
// (its unix VFS calls it through the PLT), libstdc++'s write and writev
// (std::ofstream). glibc's own stdio calls its internal write directly.

#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

typedef ssize_t (*WriteFn)(int, const void*, size_t);
typedef ssize_t (*PwriteFn)(int, const void*, size_t, off_t);
typedef ssize_t (*WritevFn)(int, const struct iovec*, int);
typedef int (*SyncFn)(int);

static pthread_once_t g_once = PTHREAD_ONCE_INIT;
static int g_active = 0;
static char g_path[PATH_MAX];
static unsigned long long g_budget = 0;
static int g_errno = ENOSPC;
static char g_log[PATH_MAX];
static char g_counter[PATH_MAX];
static pthread_mutex_t g_mutex = PTHREAD_MUTEX_INITIALIZER;
static unsigned long long g_written = 0;

static WriteFn real_write;
static PwriteFn real_pwrite;
static PwriteFn real_pwrite64;
static WritevFn real_writev;
static SyncFn real_fsync;
static SyncFn real_fdatasync;

static int ParseErrno(const char* name) {
  if (name == NULL || *name == '\0' || strcmp(name, "ENOSPC") == 0) {
    return ENOSPC;
  }
  if (strcmp(name, "EIO") == 0) return EIO;
  if (strcmp(name, "EDQUOT") == 0) return EDQUOT;
  const int number = atoi(name);
  return number > 0 ? number : ENOSPC;
}

static void Initialize(void) {
  real_write = (WriteFn)dlsym(RTLD_NEXT, "write");
  real_pwrite = (PwriteFn)dlsym(RTLD_NEXT, "pwrite");
  real_pwrite64 = (PwriteFn)dlsym(RTLD_NEXT, "pwrite64");
  real_writev = (WritevFn)dlsym(RTLD_NEXT, "writev");
  real_fsync = (SyncFn)dlsym(RTLD_NEXT, "fsync");
  real_fdatasync = (SyncFn)dlsym(RTLD_NEXT, "fdatasync");

  const char* path = getenv("COLMAP_GCN_FAULT_PATH");
  if (path == NULL || *path == '\0') return;
  const char* exe = getenv("COLMAP_GCN_FAULT_EXE");
  if (exe != NULL && *exe != '\0') {
    char wanted[PATH_MAX];
    char self[PATH_MAX];
    if (realpath(exe, wanted) == NULL ||
        realpath("/proc/self/exe", self) == NULL || strcmp(wanted, self) != 0) {
      return;
    }
  }
  snprintf(g_path, sizeof(g_path), "%s", path);
  const char* after = getenv("COLMAP_GCN_FAULT_AFTER_BYTES");
  g_budget = after != NULL ? strtoull(after, NULL, 10) : 0;
  g_errno = ParseErrno(getenv("COLMAP_GCN_FAULT_ERRNO"));
  const char* log = getenv("COLMAP_GCN_FAULT_LOG");
  if (log != NULL) snprintf(g_log, sizeof(g_log), "%s", log);
  const char* counter = getenv("COLMAP_GCN_FAULT_COUNTER");
  if (counter != NULL) snprintf(g_counter, sizeof(g_counter), "%s", counter);
  g_active = 1;
}

static void EnsureInitialized(void) { pthread_once(&g_once, Initialize); }

// Whether fd is a file the fault applies to; its path in *path.
static int Targets(int fd, char* path, size_t size) {
  if (!g_active) return 0;
  char link[64];
  snprintf(link, sizeof(link), "/proc/self/fd/%d", fd);
  const ssize_t length = readlink(link, path, size - 1);
  if (length <= 0) return 0;
  path[length] = '\0';
  if (strstr(path, g_path) == NULL) return 0;
  const size_t path_length = strlen(path);
  const int is_shm =
      path_length > 4 && strcmp(path + path_length - 4, "-shm") == 0;
  return g_errno == EIO || !is_shm;
}

// Appends one line with the real write, which never comes back here.
static void Record(const char* call, const char* path, size_t count) {
  if (g_log[0] == '\0') return;
  const int fd = open(g_log, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return;
  char line[PATH_MAX + 160];
  const int length = snprintf(line,
                              sizeof(line),
                              "pid %d %s %zu bytes to %s (budget %llu): %s\n",
                              (int)getpid(),
                              call,
                              count,
                              path,
                              g_budget,
                              strerror(g_errno));
  if (length > 0) {
    real_write(
        fd,
        line,
        (size_t)length < sizeof(line) ? (size_t)length : sizeof(line) - 1);
  }
  close(fd);
}

// After an EIO the count is kTripped: every later write fails.
static const unsigned long long kTripped = ~0ULL;

// Adds count to *written unless that exceeds the budget; 1 when it fails.
static int Spend(unsigned long long* written, size_t count) {
  if (*written == kTripped) return 1;
  if (count > g_budget - *written) {
    if (g_errno == EIO) *written = kTripped;
    return 1;
  }
  *written += count;
  return 0;
}

// Spend() on the count kept in g_counter, under an exclusive flock. The
// real pread/pwrite keep the counter's own I/O out of the count.
static int SpendShared(size_t count, unsigned long long* written) {
  const int fd = open(g_counter, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return Spend(&g_written, count);
  flock(fd, LOCK_EX);
  *written = 0;
  if (pread(fd, written, sizeof(*written), 0) != sizeof(*written)) {
    *written = 0;
  }
  const int fail = Spend(written, count);
  real_pwrite(fd, written, sizeof(*written), 0);
  flock(fd, LOCK_UN);
  close(fd);
  return fail;
}

// 1 when a write of count bytes to fd must fail, else 0 (and the bytes are
// counted against the budget).
static int ShouldFail(const char* call, int fd, size_t count) {
  EnsureInitialized();
  char path[PATH_MAX];
  if (!Targets(fd, path, sizeof(path))) return 0;
  pthread_mutex_lock(&g_mutex);
  unsigned long long written = g_written;
  const int fail = g_counter[0] != '\0' ? SpendShared(count, &written)
                                        : Spend(&g_written, count);
  if (fail) Record(call, path, count);
  pthread_mutex_unlock(&g_mutex);
  return fail;
}

static int ShouldFailSync(const char* call, int fd) {
  EnsureInitialized();
  if (g_errno != EIO) return 0;
  char path[PATH_MAX];
  if (!Targets(fd, path, sizeof(path))) return 0;
  pthread_mutex_lock(&g_mutex);
  unsigned long long written = g_written;
  if (g_counter[0] != '\0') SpendShared(0, &written);
  const int fail = written == kTripped;
  if (fail) Record(call, path, 0);
  pthread_mutex_unlock(&g_mutex);
  return fail;
}

ssize_t write(int fd, const void* buffer, size_t count) {
  if (ShouldFail("write", fd, count)) {
    errno = g_errno;
    return -1;
  }
  return real_write(fd, buffer, count);
}

ssize_t pwrite(int fd, const void* buffer, size_t count, off_t offset) {
  if (ShouldFail("pwrite", fd, count)) {
    errno = g_errno;
    return -1;
  }
  return real_pwrite(fd, buffer, count, offset);
}

ssize_t pwrite64(int fd, const void* buffer, size_t count, off_t offset) {
  if (ShouldFail("pwrite64", fd, count)) {
    errno = g_errno;
    return -1;
  }
  return real_pwrite64(fd, buffer, count, offset);
}

ssize_t writev(int fd, const struct iovec* iov, int iovcnt) {
  size_t count = 0;
  for (int i = 0; i < iovcnt; ++i) count += iov[i].iov_len;
  if (ShouldFail("writev", fd, count)) {
    errno = g_errno;
    return -1;
  }
  return real_writev(fd, iov, iovcnt);
}

int fsync(int fd) {
  if (ShouldFailSync("fsync", fd)) {
    errno = g_errno;
    return -1;
  }
  return real_fsync(fd);
}

int fdatasync(int fd) {
  if (ShouldFailSync("fdatasync", fd)) {
    errno = g_errno;
    return -1;
  }
  return real_fdatasync(fd);
}
