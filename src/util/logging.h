#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
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

// Progress of a long step, e.g.
//
//   ProgressLogger progress(images.size(), "embedding", "images");
//   for (...) { ...; progress.Increment(); }
//
// On a terminal (stderr is a tty) one live line is redrawn in place (\r),
// at most every kLiveRedrawSeconds:
//
//   embedding: 17/24 images (71 %), 3.1 images/s, ETA 2 s
//
// Otherwise (CI, `| tee`) it is a LOG(INFO) line each time the work reaches
// the next 10 % of total or min_interval_seconds have passed since the last
// line. Both modes end with one LOG(INFO) line when the work is done (or the
// logger is finished or destroyed):
//
//   embedding: 24/24 images in 7.7 s (3.1 images/s)
//
// A step done within kQuietSeconds logs nothing at all (no noise from the
// many small calls). total 0 means unknown: the line shows the count and
// rate, no ETA.
// Thread-safe: workers of a ParallelFor may each call Increment().
class ProgressLogger {
 public:
  // Seconds on a monotonic clock (tests inject their own).
  using Clock = std::function<double()>;
  // Draws a live line (tests inject their own).
  using LiveWriter = std::function<void(const std::string& line)>;
  enum class Mode { kAuto, kLive, kLines };
  static constexpr double kLiveRedrawSeconds = 0.2;
  static constexpr double kQuietSeconds = 1.0;

  ProgressLogger(size_t total,
                 std::string label,
                 std::string unit = "",
                 double min_interval_seconds = 10.0,
                 Mode mode = Mode::kAuto,
                 Clock clock = {},
                 LiveWriter live_writer = {});
  ~ProgressLogger();
  ProgressLogger(const ProgressLogger&) = delete;
  ProgressLogger& operator=(const ProgressLogger&) = delete;

  // Marks n more items done.
  void Increment(size_t n = 1);
  // Sets the number of items done (a count read from elsewhere, e.g.
  // COLMAP's output); smaller than the current count is ignored.
  void Update(size_t done);
  // Logs the final line now (once).
  void Finish();

  size_t NumDone() const { return done_.load(); }
  bool IsLive() const { return live_; }

  // "embedding: 17/24 images (71 %), 3.1 images/s, ETA 2 s"; elapsed is
  // the time since the start.
  static std::string FormatLine(const std::string& label,
                                const std::string& unit,
                                size_t done,
                                size_t total,
                                double elapsed_seconds);
  // "embedding: 24/24 images in 7.7 s (3.1 images/s)".
  static std::string FormatFinalLine(const std::string& label,
                                     const std::string& unit,
                                     size_t done,
                                     size_t total,
                                     double elapsed_seconds);
  // "0.4 s", "12 s", "3 min 05 s", "2 h 07 min".
  static std::string FormatDuration(double seconds);

 private:
  void Report(size_t done);

  const size_t total_;
  const std::string label_;
  const std::string unit_;
  const double min_interval_seconds_;
  const Clock clock_;
  const LiveWriter live_writer_;
  bool live_ = false;
  std::atomic<size_t> done_{0};
  std::mutex mutex_;
  // Under mutex_:
  bool finished_ = false;
  size_t last_reported_ = 0;  // items done at the last line
  bool shown_ = false;        // a line was drawn or logged
  double start_seconds_ = 0.0;
  double last_line_seconds_ = 0.0;
};

namespace internal {

// Whether stderr is a terminal (live progress lines).
bool StderrIsTerminal();

// Draws `line` as the live line on stderr (replacing the previous one); LOG
// lines written meanwhile clear it first and redraw it after themselves.
// An empty line removes it.
void SetLiveLine(const std::string& line);

}  // namespace internal

}  // namespace colmap_gcn
