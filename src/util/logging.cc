#include "util/logging.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
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

// The live progress line on stderr, "" when none (under LogMutex).
std::string& LiveLine() {
  static std::string line;
  return line;
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
  const std::string& live = LiveLine();
  if (live.empty()) {
    std::cerr << text << std::flush;
  } else {
    std::cerr << "\r\033[K" << text << live << std::flush;
  }
  for (LogSink* sink : Sinks()) sink->Send(level_, message);
}

bool StderrIsTerminal() { return isatty(STDERR_FILENO) != 0; }

void SetLiveLine(const std::string& line) {
  const std::lock_guard<std::mutex> lock(LogMutex());
  std::string& live = LiveLine();
  if (live.empty() && line.empty()) return;
  live = line;
  std::cerr << "\r" << line << "\033[K" << std::flush;
}

}  // namespace internal

namespace {

double SteadySeconds() {
  return std::chrono::duration<double>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

std::string FormatRate(const double rate, const std::string& unit) {
  // A described unit ("images with 3 strong partners") rates by its noun.
  const std::string noun = unit.substr(0, unit.find(' '));
  if (rate < 0.1) {
    // Slow units (scenes, methods) read as time per unit: "0.0 methods/s"
    // says nothing. Units are plural nouns; their singular drops the "s".
    std::string singular = noun.empty() ? "item" : noun;
    if (singular.size() > 1 && singular.back() == 's') singular.pop_back();
    return ProgressLogger::FormatDuration(1.0 / rate) + "/" + singular;
  }
  char buffer[48];
  std::snprintf(buffer, sizeof(buffer), rate < 10.0 ? "%.1f" : "%.0f", rate);
  return std::string(buffer) + (noun.empty() ? "/s" : " " + noun + "/s");
}

std::string Count(const size_t done,
                  const size_t total,
                  const std::string& unit) {
  std::string text = std::to_string(done);
  if (total > 0) text += "/" + std::to_string(total);
  return unit.empty() ? text : text + " " + unit;
}

}  // namespace

ProgressLogger::ProgressLogger(const size_t total,
                               std::string label,
                               std::string unit,
                               const double min_interval_seconds,
                               const Mode mode,
                               Clock clock,
                               LiveWriter live_writer)
    : total_(total),
      label_(std::move(label)),
      unit_(std::move(unit)),
      min_interval_seconds_(min_interval_seconds),
      clock_(clock ? std::move(clock) : Clock(SteadySeconds)),
      live_writer_(live_writer ? std::move(live_writer)
                               : LiveWriter(internal::SetLiveLine)) {
  live_ = mode == Mode::kLive ||
          (mode == Mode::kAuto && internal::StderrIsTerminal());
  start_seconds_ = clock_();
  last_line_seconds_ = start_seconds_;
}

ProgressLogger::~ProgressLogger() { Finish(); }

void ProgressLogger::Increment(const size_t n) {
  Report(done_.fetch_add(n) + n);
}

void ProgressLogger::Update(const size_t done) {
  size_t current = done_.load();
  while (done > current && !done_.compare_exchange_weak(current, done)) {
  }
  Report(done);
}

void ProgressLogger::Report(const size_t done) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (finished_ || done <= last_reported_) return;  // stale count
  const double now = clock_();
  const double elapsed = now - start_seconds_;
  if (total_ > 0 && done >= total_) {
    finished_ = true;
    if (live_ && shown_) live_writer_("");
    if (shown_ || elapsed >= kQuietSeconds) {
      LOG(INFO) << FormatFinalLine(label_, unit_, done, total_, elapsed);
    }
    return;
  }
  if (elapsed < kQuietSeconds) return;
  const auto tenths = [this](size_t count) {
    return total_ == 0 ? size_t{0} : std::min(count, total_) * 10 / total_;
  };
  const double since_line = now - last_line_seconds_;
  const bool due = live_ ? since_line >= kLiveRedrawSeconds || !shown_
                         : tenths(done) > tenths(last_reported_) ||
                               since_line >= min_interval_seconds_;
  if (!due) return;
  const std::string line = FormatLine(label_, unit_, done, total_, elapsed);
  if (live_) {
    live_writer_(line);
  } else {
    LOG(INFO) << line;
  }
  last_reported_ = done;
  last_line_seconds_ = now;
  shown_ = true;
}

void ProgressLogger::Finish() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (live_ && shown_) live_writer_("");
  const double elapsed = clock_() - start_seconds_;
  if (shown_ || elapsed >= kQuietSeconds) {
    LOG(INFO) << FormatFinalLine(label_, unit_, done_.load(), total_, elapsed);
  }
}

std::string ProgressLogger::FormatLine(const std::string& label,
                                       const std::string& unit,
                                       const size_t done,
                                       const size_t total,
                                       const double elapsed_seconds) {
  std::string line = label + ": " + Count(done, total, unit);
  if (total > 0) {
    char percent[32];
    std::snprintf(percent,
                  sizeof(percent),
                  " (%.0f %%)",
                  100.0 * static_cast<double>(std::min(done, total)) / total);
    line += percent;
  }
  if (done == 0 || elapsed_seconds <= 0.0) return line;
  const double rate = static_cast<double>(done) / elapsed_seconds;
  line += ", " + FormatRate(rate, unit);
  if (total > done) {
    line += ", ETA " + FormatDuration(static_cast<double>(total - done) / rate);
  }
  return line;
}

std::string ProgressLogger::FormatFinalLine(const std::string& label,
                                            const std::string& unit,
                                            const size_t done,
                                            const size_t total,
                                            const double elapsed_seconds) {
  std::string line = label + ": " + Count(done, total, unit) + " in " +
                     FormatDuration(elapsed_seconds);
  if (done > 0 && elapsed_seconds > 0.0) {
    line += " (" +
            FormatRate(static_cast<double>(done) / elapsed_seconds, unit) + ")";
  }
  return line;
}

std::string ProgressLogger::FormatDuration(const double seconds) {
  char buffer[48];
  const double s = std::max(0.0, seconds);
  if (s < 10.0) {
    std::snprintf(buffer, sizeof(buffer), "%.1f s", s);
  } else if (s < 60.0) {
    std::snprintf(buffer, sizeof(buffer), "%.0f s", s);
  } else if (s < 3600.0) {
    const long total = std::lround(s);
    std::snprintf(
        buffer, sizeof(buffer), "%ld min %02ld s", total / 60, total % 60);
  } else {
    const long minutes = std::lround(s / 60.0);
    std::snprintf(
        buffer, sizeof(buffer), "%ld h %02ld min", minutes / 60, minutes % 60);
  }
  return buffer;
}

}  // namespace colmap_gcn
