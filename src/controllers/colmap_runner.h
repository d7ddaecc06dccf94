#pragma once

#include <functional>
#include <string>
#include <vector>

namespace colmap_gcn {

struct ColmapRunnerOptions {
  // Path of the real COLMAP binary; empty: $COLMAP_EXE, else the first
  // `colmap` on PATH that is not this front end.
  std::string colmap_exe = "";

  // Every COLMAP invocation and its full output are appended here; empty
  // keeps no log.
  std::string log_path = "";

  // Echo all of COLMAP's output (otherwise its progress is summarised:
  // "extracting features: 17/24 images (71 %), 3.1 images/s, ETA 2 s").
  bool verbose = false;

  // Summarise COLMAP's progress at all.
  bool show_progress = true;
};

// Finds the real COLMAP as described above; throws Error if none is found.
std::string FindColmapExecutable(const std::string& hint = "");

// Runs real COLMAP subcommands headless: CPU-only flags are added to the
// commands that would otherwise try to open an OpenGL context, output goes
// to the log, and failures throw Error naming the command with the tail of
// COLMAP's output.
class ColmapRunner {
 public:
  explicit ColmapRunner(const ColmapRunnerOptions& options = {});

  const std::string& Executable() const { return exe_; }

  // "3.8" etc., from `colmap help`. Throws if the binary is not COLMAP.
  const std::string& Version() const { return version_; }

  // Runs `colmap command args...` and returns its combined output. Throws
  // Error when COLMAP fails, and also when it exits 0 having reported a
  // failure it does not act on (COLMAP 3.8 logs a failed SQLite write and
  // goes on): the message names the cause (DiagnoseColmapOutput).
  std::string Run(const std::string& command,
                  std::vector<std::string> args) const;

  // COLMAP commands started so far (`help` aside): a caller that fails
  // before the first knows that nothing of COLMAP's is there to resume.
  int NumRuns() const { return num_runs_; }

 private:
  ColmapRunnerOptions options_;
  std::string exe_;
  std::string version_;
  mutable int num_runs_ = 0;
};

// The failure COLMAP's output reports, in a few words naming the cause
// ("the disk is full (SQLite: database or disk is full)"), or "" when it
// reports none. Recognises SQLite's error lines, glog's "Check failed" and
// uncaught C++ exceptions.
std::string DiagnoseColmapOutput(const std::string& output);

// Asks COLMAP to parse the options meant for it before anything runs:
// `colmap <command> <options> -h` parses them and exits. ImageReader.* and
// SiftExtraction.* go to feature_extractor, SiftMatching.* to
// matches_importer, Mapper.* to mapper. Throws Error naming the option COLMAP
// rejects (an unknown name, a malformed value). COLMAP is looked for
// (FindColmapExecutable(colmap_exe)) only when args hold such options.
void CheckColmapArguments(const std::vector<std::string>& args,
                          const std::string& colmap_exe = "");
// A progress count in one line of COLMAP's output.
struct ColmapProgress {
  std::string label;  // "extracting features", "matching", "registering"
  std::string unit;   // "images", "blocks"
  size_t done = 0;
  size_t total = 0;  // 0: unknown (the mapper's registered images)
};

// Reads COLMAP 3.8's progress lines ("Processed file [3/24]", exhaustive's
// "Matching block [1/3, 2/3]", "Matching image [4/24]", "Indexing image
// [..]", "Registering image #7 (5)"); false for others. matches_importer's
// "Matching block [1/1]" comes only at its end: MatchPairGenerator counts
// those pairs itself.
bool ParseColmapProgress(const std::string& line, ColmapProgress* progress);

// The arguments COLMAP 3.8 needs to run `command` without a GPU/display,
// unless args already set them.
std::vector<std::string> HeadlessArguments(
    const std::string& command, const std::vector<std::string>& args);

// Runs a program (no shell) and captures stdout+stderr. Each output line is
// passed to on_line as it arrives. Returns the exit status; a program killed
// by a signal returns 128 + signal, as a shell would.
int RunProcess(const std::string& exe,
               const std::vector<std::string>& args,
               std::string* output,
               const std::function<void(const std::string&)>& on_line = {});

}  // namespace colmap_gcn
