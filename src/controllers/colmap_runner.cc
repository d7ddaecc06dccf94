#include "controllers/colmap_runner.h"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>

#include "util/error.h"
#include "util/file.h"
#include "util/interrupt.h"
#include "util/logging.h"
#include "util/option_manager.h"
#include "util/string.h"

extern char** environ;

namespace colmap_gcn {
namespace {

namespace fs = std::filesystem;

std::string CanonicalPath(const std::string& path) {
  std::error_code ec;
  const fs::path canonical = fs::canonical(path, ec);
  return ec ? path : canonical.string();
}

std::string SelfExecutable() { return CanonicalPath("/proc/self/exe"); }

bool IsExecutableFile(const std::string& path) {
  return ExistsFile(path) && access(path.c_str(), X_OK) == 0;
}

std::string TailLines(const std::string& text, size_t num_lines) {
  std::vector<std::string> lines = StringSplit(StringTrim(text), "\n");
  if (lines.size() > num_lines) {
    lines.erase(lines.begin(), lines.end() - num_lines);
  }
  return StringJoin(lines, " | ");
}

// SQLite's messages (sqlite3_errstr) for the failures a user can act on, in
// the user's words.
struct SqliteCause {
  const char* message;
  const char* cause;
};
const SqliteCause kSqliteCauses[] = {
    {"database or disk is full", "the disk is full"},
    {"disk I/O error", "a disk I/O error"},
    {"database is locked", "the database is locked by another program"},
    {"attempt to write a readonly database", "the database is read-only"},
    {"unable to open database file", "the database file cannot be opened"},
    {"database disk image is malformed", "the database is damaged"},
    {"out of memory", "out of memory"},
};

}  // namespace

bool ParseColmapProgress(const std::string& line, ColmapProgress* progress) {
  struct Pattern {
    std::regex regex;
    const char* label;
    const char* unit;
  };
  static const Pattern kPatterns[] = {
      {std::regex(R"(Processed file \[(\d+)/(\d+)\])"),
       "extracting features",
       "images"},
      {std::regex(R"(Matching image \[(\d+)/(\d+)\])"), "matching", "images"},
      {std::regex(R"(Indexing image \[(\d+)/(\d+)\])"), "indexing", "images"},
      {std::regex(R"(Querying for image .*\[(\d+)/(\d+)\])"),
       "retrieving",
       "images"},
  };
  std::smatch match;
  for (const Pattern& pattern : kPatterns) {
    if (std::regex_search(line, match, pattern.regex)) {
      *progress = {pattern.label,
                   pattern.unit,
                   std::stoul(match[1].str()),
                   std::stoul(match[2].str())};
      return true;
    }
  }
  // Exhaustive matching: block (i, j) of n x m, row-major.
  static const std::regex kBlock2D(
      R"(Matching block \[(\d+)/(\d+), (\d+)/(\d+)\])");
  if (std::regex_search(line, match, kBlock2D)) {
    const size_t i = std::stoul(match[1].str());
    const size_t n = std::stoul(match[2].str());
    const size_t j = std::stoul(match[3].str());
    const size_t m = std::stoul(match[4].str());
    *progress = {"matching", "blocks", (i - 1) * m + j, n * m};
    return true;
  }
  static const std::regex kRegistering(R"(Registering image #\d+ \((\d+)\))");
  if (std::regex_search(line, match, kRegistering)) {
    *progress = {"registering", "images", std::stoul(match[1].str()), 0};
    return true;
  }
  return false;
}

std::string DiagnoseColmapOutput(const std::string& output) {
  // The first report is the cause; later lines are mostly its consequences.
  static const std::regex kSqlite(R"(SQLite error[^:]*: *(.*))");
  static const std::regex kCheck(R"((Check failed: .*))");
  static const std::regex kTerminate(
      R"(terminate called after throwing an instance of '([^']*)')");
  static const std::regex kWhat(R"(^\s*what\(\): *(.*))");
  std::vector<std::string> lines = StringSplit(output, "\n");
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string line = StringTrim(lines[i]);
    std::smatch match;
    if (std::regex_search(line, match, kSqlite)) {
      const std::string message = StringTrim(match[1].str());
      for (const SqliteCause& known : kSqliteCauses) {
        if (message.find(known.message) != std::string::npos) {
          return std::string(known.cause) + " (SQLite: " + message + ")";
        }
      }
      return "a database error (SQLite: " + message + ")";
    }
    if (std::regex_search(line, match, kCheck)) {
      return "COLMAP's own check failed (" + match[1].str() + ")";
    }
    if (std::regex_search(line, match, kTerminate)) {
      const std::string type = match[1].str();
      std::string what;
      if (i + 1 < lines.size() &&
          std::regex_search(lines[i + 1], match, kWhat)) {
        what = ": " + StringTrim(match[1].str());
      }
      return "COLMAP aborted on an uncaught " + type + what;
    }
  }
  return "";
}

std::string FindColmapExecutable(const std::string& hint) {
  const std::string self = SelfExecutable();
  auto usable = [&](const std::string& path) {
    return IsExecutableFile(path) && CanonicalPath(path) != self;
  };
  if (!hint.empty()) {
    if (!usable(hint)) {
      ThrowError("COLMAP executable not usable: ", hint);
    }
    return hint;
  }
  const char* env = std::getenv("COLMAP_EXE");
  if (env != nullptr && *env != '\0') {
    if (!usable(env)) {
      ThrowError("COLMAP_EXE=", env, " is not an executable COLMAP");
    }
    return env;
  }
  const char* path = std::getenv("PATH");
  for (const std::string& dir : StringSplit(path ? path : "", ":")) {
    if (dir.empty()) continue;
    const std::string candidate = JoinPaths(dir, "colmap");
    if (usable(candidate)) {
      return candidate;
    }
  }
  ThrowError(
      "COLMAP not found: install it (scripts/install_deps.sh) or set "
      "COLMAP_EXE to the real colmap binary");
}

void CheckColmapArguments(const std::vector<std::string>& args,
                          const std::string& colmap_exe) {
  struct ColmapCommand {
    const char* name;
    std::vector<std::string> prefixes;
  };
  const ColmapCommand kCommands[] = {
      {"feature_extractor", {"ImageReader.", "SiftExtraction."}},
      {"matches_importer", {"SiftMatching."}},
      {"mapper", {"Mapper."}},
  };
  for (const ColmapCommand& command : kCommands) {
    std::vector<std::string> check =
        ArgumentsWithPrefix(args, command.prefixes);
    if (check.empty()) continue;
    check.insert(check.begin(), command.name);
    check.push_back("-h");
    std::string output;
    if (RunProcess(FindColmapExecutable(colmap_exe), check, &output) == 0) {
      continue;
    }
    std::string reason = "exit status != 0";
    for (const std::string& line : StringSplit(output, "\n")) {
      const size_t error = line.find("ERROR: ");
      if (error == std::string::npos) continue;
      reason = line.substr(error + 7);
      for (const char* noise :
           {"Failed to parse options - ", "Failed to parse options "}) {
        if (StringStartsWith(reason, noise)) {
          reason = reason.substr(std::strlen(noise));
        }
      }
      break;
    }
    ThrowError("COLMAP's ",
               command.name,
               " rejects its options: ",
               StringTrim(reason));
  }
}

std::vector<std::string> HeadlessArguments(
    const std::string& command, const std::vector<std::string>& args) {
  auto has = [&](const std::string& option) {
    return std::any_of(args.begin(), args.end(), [&](const std::string& arg) {
      return StringStartsWith(arg, option);
    });
  };
  std::vector<std::string> extra;
  if (command == "feature_extractor" && !has("--SiftExtraction.use_gpu")) {
    extra = {"--SiftExtraction.use_gpu", "0"};
  }
  const bool is_matcher =
      command.size() > 8 &&
      command.compare(command.size() - 8, 8, "_matcher") == 0;
  if ((is_matcher || command == "matches_importer") &&
      !has("--SiftMatching.use_gpu")) {
    extra = {"--SiftMatching.use_gpu", "0"};
  }
  return extra;
}

int RunProcess(const std::string& exe,
               const std::vector<std::string>& args,
               std::string* output,
               const std::function<void(const std::string&)>& on_line) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) {
    ThrowError("cannot create a pipe to run ", exe);
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[1]);

  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(exe.c_str()));
  for (const auto& arg : args) {
    argv.push_back(const_cast<char*>(arg.c_str()));
  }
  argv.push_back(nullptr);

  pid_t pid;
  const int spawn_error =
      posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_fds[1]);
  if (spawn_error != 0) {
    close(pipe_fds[0]);
    ThrowError("cannot run ", exe, ": ", std::strerror(spawn_error));
  }
  SetInterruptibleChild(pid);

  std::string captured;
  std::string partial_line;
  char buffer[4096];
  ssize_t n;
  while ((n = read(pipe_fds[0], buffer, sizeof(buffer))) != 0) {
    if (n < 0) {
      if (errno == EINTR) continue;
      break;
    }
    captured.append(buffer, n);
    partial_line.append(buffer, n);
    size_t newline;
    while ((newline = partial_line.find('\n')) != std::string::npos) {
      if (on_line) on_line(partial_line.substr(0, newline));
      partial_line.erase(0, newline + 1);
    }
  }
  if (on_line && !partial_line.empty()) on_line(partial_line);
  close(pipe_fds[0]);

  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  SetInterruptibleChild(0);
  if (output != nullptr) {
    *output = std::move(captured);
  }
  if (WIFSIGNALED(status)) {
    return 128 + WTERMSIG(status);
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

ColmapRunner::ColmapRunner(const ColmapRunnerOptions& options)
    : options_(options), exe_(FindColmapExecutable(options.colmap_exe)) {
  std::string output;
  RunProcess(exe_, {"help"}, &output);
  static const std::regex kVersion(R"(COLMAP (\d+)\.(\d+)(\.\d+)?)");
  std::smatch match;
  if (!std::regex_search(output, match, kVersion)) {
    ThrowError(exe_,
               " does not look like COLMAP (`",
               exe_,
               " help` printed no version)");
  }
  version_ = match[1].str() + "." + match[2].str() + match[3].str();
  const int major = std::stoi(match[1].str());
  const int minor = std::stoi(match[2].str());
  // The option names we pass (--SiftMatching.*, matches_importer) are those
  // of COLMAP 3.6-3.9; later releases renamed them.
  if (major != 3 || minor < 6 || minor > 9) {
    ThrowError("unsupported COLMAP ",
               version_,
               " at ",
               exe_,
               ": colmap-gcn drives COLMAP 3.6-3.9");
  }
}

std::string ColmapRunner::Run(const std::string& command,
                              std::vector<std::string> args) const {
  const std::vector<std::string> extra = HeadlessArguments(command, args);
  args.insert(args.end(), extra.begin(), extra.end());
  args.insert(args.begin(), command);

  std::vector<std::string> quoted;
  for (const auto& arg : args) quoted.push_back(ShellQuote(arg));
  const std::string command_line =
      ShellQuote(exe_) + " " + StringJoin(quoted, " ");

  std::ofstream log;
  if (!options_.log_path.empty()) {
    log.open(options_.log_path, std::ios::app);
    log << "$ " << command_line << "\n";
  }
  ++num_runs_;
  std::string output;
  // One progress logger per stage COLMAP reports (the mapper's registering
  // follows no other stage; exhaustive matching has one).
  std::unique_ptr<ProgressLogger> progress;
  std::string progress_key;
  const int status =
      RunProcess(exe_, args, &output, [&](const std::string& line) {
        if (options_.verbose) {
          LOG(INFO) << "[colmap " << command << "] " << line;
          return;
        }
        ColmapProgress parsed;
        if (!options_.show_progress || !ParseColmapProgress(line, &parsed)) {
          return;
        }
        const std::string key =
            parsed.label + "/" + std::to_string(parsed.total);
        if (progress == nullptr || key != progress_key ||
            parsed.done < progress->NumDone()) {
          progress.reset();  // logs the previous stage's final line
          progress = std::make_unique<ProgressLogger>(
              parsed.total, parsed.label, parsed.unit);
          progress_key = key;
        }
        progress->Update(parsed.done);
      });
  progress.reset();
  if (log.is_open()) {
    log << output << "[exit " << status << "]\n";
  }
  // Also after a child that ended normally: the signal asked this run to
  // stop, and the next step must not start.
  if (PendingInterrupt() != 0) {
    ThrowError("interrupted (signal ",
               PendingInterrupt(),
               ") while colmap ",
               command,
               " ran");
  }
  const std::string cause = DiagnoseColmapOutput(output);
  if (status != 0) {
    const std::string why =
        status > 128 ? "crashed (signal " + std::to_string(status - 128) + ")"
                     : "failed (exit " + std::to_string(status) + ")";
    if (!cause.empty()) {
      ThrowError("colmap ", command, " ", why, ": ", cause);
    }
    ThrowError("colmap ",
               command,
               " ",
               why,
               ": ",
               command_line,
               " -- last output: ",
               TailLines(output, 3));
  }
  if (!cause.empty()) {
    ThrowError("colmap ",
               command,
               " reported ",
               cause,
               " although it exited 0",
               options_.log_path.empty() ? "" : " (its output is in ",
               options_.log_path,
               options_.log_path.empty() ? "" : ")");
  }
  return output;
}

}  // namespace colmap_gcn
