#pragma once

#include <atomic>
#include <cstddef>
#include <mutex>
#include <sstream>
#include <string>

#include "util/timer.h"

namespace colmap_gcn {

// Diagnostics of the library and the commands, COLMAP style:
//
//   LOG(INFO) << "matching " << pairs.size() << " pairs";
//
// writes one line to stderr with glog's prefix (level letter, month, day,
// local time, source file and line):
//
//   I0612 14:03:21 pair_matching.cc:57] matching 1225 pairs
//
// A command's real output (tables, results, --help) goes to stdout with
// plain prints instead; errors reach the user as exceptions (util/error.h),
// which the front end prints as one `ERROR: ...` line.
enum class LogLevel { kInfo = 0, kWarning = 1, kError = 2 };

// Messages below the minimum level are dropped (default kInfo: all).
void SetMinLogLevel(LogLevel level);
LogLevel MinLogLevel();
bool IsLogLevelEnabled(LogLevel level);

// Receives every message that passes the level filter, without the prefix,
// besides stderr (tests read what a component logged through one).
class LogSink {
 public:
  virtual ~LogSink() = default;
  virtual void Send(LogLevel level, const std::string& message) = 0;
};

// Registers a sink for its lifetime. Sinks are called under the logging
// lock, one message at a time.
class ScopedLogSink {
 public:
  explicit ScopedLogSink(LogSink* sink);
  ~ScopedLogSink();
  ScopedLogSink(const ScopedLogSink&) = delete;
  ScopedLogSink& operator=(const ScopedLogSink&) = delete;

 private:
  LogSink* sink_;
};

namespace internal {

// One message; written (thread-safely, as one line) when destroyed.
class LogMessage {
 public:
  LogMessage(LogLevel level, const char* file, int line);
  ~LogMessage();
  LogMessage(const LogMessage&) = delete;
  LogMessage& operator=(const LogMessage&) = delete;
  std::ostream& stream() { return stream_; }

 private:
  LogLevel level_;
  const char* file_;
  int line_;
  std::ostringstream stream_;
};

// Turns the streamed expression into void so that LOG fits in a ?:.
struct LogVoidify {
  void operator&(std::ostream&) {}
};

// The prefix LOG writes before a message, e.g. "I0612 14:03:21 file.cc:42] ".
std::string LogPrefix(LogLevel level, const char* file, int line);

}  // namespace internal

#define COLMAP_GCN_LOG_LEVEL_INFO ::colmap_gcn::LogLevel::kInfo
#define COLMAP_GCN_LOG_LEVEL_WARNING ::colmap_gcn::LogLevel::kWarning
#define COLMAP_GCN_LOG_LEVEL_ERROR ::colmap_gcn::LogLevel::kError

// LOG(INFO), LOG(WARNING), LOG(ERROR). The streamed arguments are not
// evaluated when the level is disabled.
#define LOG(level)                                                \
  !::colmap_gcn::IsLogLevelEnabled(COLMAP_GCN_LOG_LEVEL_##level)  \
      ? (void)0                                                   \
      : ::colmap_gcn::internal::LogVoidify() &                    \
            ::colmap_gcn::internal::LogMessage(                   \
                COLMAP_GCN_LOG_LEVEL_##level, __FILE__, __LINE__) \
                .stream()

// A progress line for long loops: LOG(INFO) "label: i/N (x %)" when the
// work reaches the next 10 % of total, or min_interval_seconds have passed
// since the last line, and always when it is done. Thread-safe: workers of
// a ParallelFor may each call Increment().
class ProgressLogger {
 public:
  ProgressLogger(size_t total,
                 std::string label,
                 double min_interval_seconds = 10.0);

  // Marks n more items done.
  void Increment(size_t n = 1);
  size_t NumDone() const { return done_.load(); }

  // The line for i of total items, e.g. "embedding: 12/40 (30 %)".
  static std::string FormatLine(const std::string& label,
                                size_t done,
                                size_t total);

 private:
  const size_t total_;
  const std::string label_;
  const double min_interval_seconds_;
  std::atomic<size_t> done_{0};
  std::mutex mutex_;
  size_t last_logged_ = 0;  // items done at the last line (under mutex_)
  Timer since_last_line_;
};

}  // namespace colmap_gcn
