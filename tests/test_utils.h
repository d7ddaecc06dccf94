#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "util/logging.h"

namespace colmap_gcn {
namespace test {

// ../shared/datasets beside the repository, or "" when absent (tests that
// need it call GTEST_SKIP()).
std::string SharedDatasetsDir();

// The real COLMAP binary (COLMAP_EXE or PATH), or "" when not installed.
std::string RealColmapExe();

// Our `colmap` front end built by this tree.
std::string FrontendExe();

// Runs a shell command, capturing stdout+stderr into *output (if non-null).
// Returns the exit code (or -1 if it could not run).
int RunShell(const std::string& command, std::string* output = nullptr);

// COLMAP 3.8's CREATE TABLE statements (as `.schema` prints them for a
// database made by `colmap database_creator`), for hand-made databases.
extern const char* const kColmap38Schema;

// Expects function to throw colmap_gcn::Error with a one-line message that
// contains expected.
void ExpectErrorContaining(const std::function<void()>& function,
                           const std::string& expected);

// argv as COLMAP commands see it (argv[0] is the command name), for
// parsing options in tests.
class Argv {
 public:
  explicit Argv(std::vector<std::string> args) : args_(std::move(args)) {
    for (auto& arg : args_) pointers_.push_back(arg.data());
  }
  int argc() { return static_cast<int>(pointers_.size()); }
  char** argv() { return pointers_.data(); }

 private:
  std::vector<std::string> args_;
  std::vector<char*> pointers_;
};

// The messages LOG writes while it is registered (with ScopedLogSink), in
// order, without their prefix.
class LogLines : public LogSink {
 public:
  void Send(LogLevel level, const std::string& message) override;
  size_t size() const { return messages_.size(); }
  const std::string& operator[](size_t i) const { return messages_.at(i); }

 private:
  std::vector<std::string> messages_;
};

}  // namespace test
}  // namespace colmap_gcn
