#pragma once

#include <string>
#include <vector>

namespace colmap_gcn {
namespace test {

// What one run of the built `colmap` front end left.
struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs `colmap <args>` with the build's bin dir first on PATH (and env,
// "NAME=value ...", set), stdout and stderr captured separately.
CommandResult RunColmap(const std::string& args, const std::string& env = "");

// Exit 1, stderr one "ERROR: " line holding every needle (the flag, the
// value, the allowed range...).
void ExpectOneLineError(const CommandResult& result,
                        const std::vector<std::string>& needles);

}  // namespace test
}  // namespace colmap_gcn
