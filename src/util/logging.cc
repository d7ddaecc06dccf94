#include "util/logging.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <iostream>
#include <utility>
#include <vector>

namespace colmap_gcn {
namespace {

std::atomic<int> min_log_level{static_cast<int>(LogLevel::kInfo)};

// Guards stderr writes and the sink list, so that lines of different
// threads never interleave.
std::mutex& LogMutex() {
  static std::mutex mutex;
  return mutex;
}

std::vector<LogSink*>& Sinks() {
  static std::vector<LogSink*> sinks;
  return sinks;
}

char LevelLetter(LogLevel level) {
  switch (level) {
    case LogLevel::kInfo:
      return 'I';
    case LogLevel::kWarning:
      return 'W';
    case LogLevel::kError:
      return 'E';
  }
  return '?';
}

}  // namespace

void SetMinLogLevel(const LogLevel level) {
  min_log_level = static_cast<int>(level);
}

LogLevel MinLogLevel() { return static_cast<LogLevel>(min_log_level.load()); }

bool IsLogLevelEnabled(const LogLevel level) {
  return static_cast<int>(level) >= min_log_level.load();
}

ScopedLogSink::ScopedLogSink(LogSink* sink) : sink_(sink) {
  const std::lock_guard<std::mutex> lock(LogMutex());
  Sinks().push_back(sink_);
}

ScopedLogSink::~ScopedLogSink() {
  const std::lock_guard<std::mutex> lock(LogMutex());
  std::vector<LogSink*>& sinks = Sinks();
  sinks.erase(std::remove(sinks.begin(), sinks.end(), sink_), sinks.end());
}

namespace internal {

std::string LogPrefix(const LogLevel level, const char* file, const int line) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char time_buffer[32];
  std::strftime(time_buffer, sizeof(time_buffer), "%m%d %H:%M:%S", &local);
  const char* slash = std::strrchr(file, '/');
  const char* base = slash ? slash + 1 : file;
  return std::string(1, LevelLetter(level)) + time_buffer + " " + base + ":" +
         std::to_string(line) + "] ";
}

LogMessage::LogMessage(const LogLevel level, const char* file, const int line)
    : level_(level), file_(file), line_(line) {}

LogMessage::~LogMessage() {
  const std::string message = stream_.str();
  const std::string text = LogPrefix(level_, file_, line_) + message + "\n";
  const std::lock_guard<std::mutex> lock(LogMutex());
  std::cerr << text << std::flush;
  for (LogSink* sink : Sinks()) sink->Send(level_, message);
}

}  // namespace internal

ProgressLogger::ProgressLogger(const size_t total,
                               std::string label,
                               const double min_interval_seconds)
    : total_(total),
      label_(std::move(label)),
      min_interval_seconds_(min_interval_seconds) {}

void ProgressLogger::Increment(const size_t n) {
  const size_t done = done_.fetch_add(n) + n;
  const std::lock_guard<std::mutex> lock(mutex_);
  if (done <= last_logged_) return;  // a later count was logged already
  // Tenths of the total reached: a line each time it grows.
  const auto tenths = [this](size_t count) {
    return total_ == 0 ? size_t{10} : std::min(count, total_) * 10 / total_;
  };
  const bool finished = done >= total_;
  if (finished || tenths(done) > tenths(last_logged_) ||
      since_last_line_.ElapsedSeconds() >= min_interval_seconds_) {
    LOG(INFO) << FormatLine(label_, done, total_);
    last_logged_ = done;
    since_last_line_.Restart();
  }
}

std::string ProgressLogger::FormatLine(const std::string& label,
                                       const size_t done,
                                       const size_t total) {
  const double percent =
      total == 0 ? 100.0 : 100.0 * static_cast<double>(done) / total;
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), " (%.0f %%)", percent);
  return label + ": " + std::to_string(done) + "/" + std::to_string(total) +
         buffer;
}

}  // namespace colmap_gcn
