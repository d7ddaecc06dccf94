// The write-fault injector the fault-injection suite runs COLMAP under
// (fault_injector.c), on programs whose writes are easy to see: dd (write)
// and the sqlite3 shell (SQLite's pwrite64, as inside COLMAP). A broken
// injector would otherwise let that suite pass without any fault.

#include <sys/stat.h>

#include <string>

#include <gtest/gtest.h>

#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

using test::RunShell;

class FaultInjector : public testing::Test {
 protected:
  void SetUp() override {
    target_ = JoinPaths(dir_.Path(), "target.bin");
    log_ = JoinPaths(dir_.Path(), "fault.log");
  }

  // The environment that faults writes to files containing path after
  // after_bytes, with error, in the program exe (all programs if empty).
  std::string Environment(const std::string& path,
                          const int after_bytes,
                          const std::string& error,
                          const std::string& exe = "") const {
    return "LD_PRELOAD=" + ShellQuote(COLMAP_GCN_FAULT_INJECTOR) +
           " COLMAP_GCN_FAULT_EXE=" + ShellQuote(exe) +
           " COLMAP_GCN_FAULT_PATH=" + ShellQuote(path) +
           " COLMAP_GCN_FAULT_AFTER_BYTES=" + std::to_string(after_bytes) +
           " COLMAP_GCN_FAULT_ERRNO=" + error +
           " COLMAP_GCN_FAULT_LOG=" + ShellQuote(log_);
  }

  // dd writing count blocks of 512 bytes to target_ under env.
  int Dd(const std::string& env, const int count, std::string* output) {
    return RunShell("env " + env +
                        " dd if=/dev/zero of=" + ShellQuote(target_) +
                        " bs=512 count=" + std::to_string(count),
                    output);
  }

  std::string Log() const { return ExistsFile(log_) ? ReadTextFile(log_) : ""; }

  off_t TargetSize() const {
    struct stat info;
    return stat(target_.c_str(), &info) == 0 ? info.st_size : -1;
  }

  TemporaryDirectory dir_{"colmap_gcn_fault_injector"};
  std::string target_;
  std::string log_;
};

TEST_F(FaultInjector, WritesPastTheBudgetFailWithNoSpace) {
  std::string output;
  EXPECT_NE(Dd(Environment("target.bin", 1000, "ENOSPC"), 4, &output), 0);
  EXPECT_NE(output.find("No space left on device"), std::string::npos)
      << output;
  // The first 512 bytes fit, the next write does not and fails whole.
  EXPECT_EQ(TargetSize(), 512);
  const std::string log = Log();
  EXPECT_NE(log.find("write 512 bytes to " + target_), std::string::npos)
      << log;
  EXPECT_NE(log.find("No space left on device"), std::string::npos) << log;
}

TEST_F(FaultInjector, WritesPastTheBudgetFailWithAnIoError) {
  std::string output;
  EXPECT_NE(Dd(Environment("target.bin", 0, "EIO"), 2, &output), 0);
  EXPECT_NE(output.find("Input/output error"), std::string::npos) << output;
  EXPECT_EQ(TargetSize(), 0);
  EXPECT_FALSE(Log().empty());
}

TEST_F(FaultInjector, OtherFilesAndProgramsAreLeftAlone) {
  std::string output;
  // Another file name.
  EXPECT_EQ(Dd(Environment("other.bin", 0, "ENOSPC"), 4, &output), 0) << output;
  EXPECT_EQ(TargetSize(), 2048);
  // Another program: only /bin/sh is named, dd runs unharmed.
  EXPECT_EQ(Dd(Environment("target.bin", 0, "ENOSPC", "/bin/sh"), 4, &output),
            0)
      << output;
  EXPECT_EQ(TargetSize(), 2048);
  EXPECT_FALSE(ExistsFile(log_));
  // Naming dd's own executable (through its symlinks) makes it act.
  std::string dd;
  ASSERT_EQ(RunShell("readlink -f \"$(command -v dd)\"", &dd), 0);
  EXPECT_NE(
      Dd(Environment("target.bin", 0, "ENOSPC", StringTrim(dd)), 4, &output), 0)
      << output;
  EXPECT_FALSE(Log().empty());
}

TEST_F(FaultInjector, SharedCounterSpansProcesses) {
  const std::string env = Environment("target.bin", 1500, "ENOSPC") +
                          " COLMAP_GCN_FAULT_COUNTER=" +
                          ShellQuote(JoinPaths(dir_.Path(), "fault.count"));
  std::string output;
  // 1024 of the 1500 bytes, then 512 more would exceed them.
  EXPECT_EQ(Dd(env, 2, &output), 0) << output;
  EXPECT_FALSE(ExistsFile(log_));
  EXPECT_NE(Dd(env, 1, &output), 0) << output;
  EXPECT_EQ(TargetSize(), 0);
  EXPECT_FALSE(Log().empty());
  // A full disk still takes what fits in its last 476 bytes.
  EXPECT_EQ(RunShell("env " + env + " dd if=/dev/zero of=" +
                         ShellQuote(target_) + " bs=476 count=1",
                     &output),
            0)
      << output;
  EXPECT_EQ(TargetSize(), 476);
}

TEST_F(FaultInjector, AfterAnIoErrorEveryWriteAndSyncFails) {
  const std::string env = Environment("target.bin", 1000, "EIO") +
                          " COLMAP_GCN_FAULT_COUNTER=" +
                          ShellQuote(JoinPaths(dir_.Path(), "fault.count"));
  std::string output;
  EXPECT_NE(Dd(env, 4, &output), 0) << output;
  EXPECT_EQ(TargetSize(), 512);
  // A write that would fit in the budget fails all the same.
  EXPECT_NE(RunShell("env " + env + " dd if=/dev/zero of=" +
                         ShellQuote(target_) + " bs=1 count=1",
                     &output),
            0)
      << output;
  // So does an fsync without any write.
  EXPECT_NE(RunShell("env " + env + " dd if=/dev/null of=" +
                         ShellQuote(target_) + " conv=fsync,notrunc",
                     &output),
            0)
      << output;
  EXPECT_NE(Log().find("fsync"), std::string::npos) << Log();
}

// SQLite's unix VFS writes with pwrite64 through its own table of system
// calls; the shell's errors are what COLMAP's SQLite reports too.
TEST_F(FaultInjector, SqliteReportsDiskFullAndIoError) {
  if (RunShell("command -v sqlite3") != 0) GTEST_SKIP() << "no sqlite3 shell";
  const std::string sql =
      "'CREATE TABLE t(x); WITH RECURSIVE c(i) AS (SELECT 1 UNION ALL SELECT "
      "i + 1 FROM c WHERE i < 1000) INSERT INTO t SELECT randomblob(100) "
      "FROM c;'";
  for (const std::string error : {"ENOSPC", "EIO"}) {
    const std::string database =
        JoinPaths(dir_.Path(), "sqlite_" + error + ".db");
    std::string output;
    EXPECT_NE(RunShell("env " + Environment(database, 10000, error) +
                           " sqlite3 " + ShellQuote(database) + " " + sql,
                       &output),
              0)
        << output;
    EXPECT_NE(output.find(error == "EIO" ? "disk I/O error"
                                         : "database or disk is full"),
              std::string::npos)
        << output;
    EXPECT_NE(Log().find("pwrite64"), std::string::npos);
  }
}

}  // namespace
}  // namespace colmap_gcn
