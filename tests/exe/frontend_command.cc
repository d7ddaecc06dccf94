#include "frontend_command.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace test {

CommandResult RunColmap(const std::string& args, const std::string& env) {
  TemporaryDirectory io("colmap_gcn_frontend_io");
  const std::string out_path = JoinPaths(io.Path(), "out");
  const std::string err_path = JoinPaths(io.Path(), "err");
  const std::string bin_dir =
      FrontendExe().substr(0, FrontendExe().find_last_of('/'));
  CommandResult result;
  result.exit_code =
      RunShell("{ " + env + " PATH=" + ShellQuote(bin_dir) + ":$PATH " +
               ShellQuote(FrontendExe()) + " " + args + " >" +
               ShellQuote(out_path) + " 2>" + ShellQuote(err_path) + "; }");
  result.out = ExistsFile(out_path) ? ReadTextFile(out_path) : "";
  result.err = ExistsFile(err_path) ? ReadTextFile(err_path) : "";
  return result;
}

void ExpectOneLineError(const CommandResult& result,
                        const std::vector<std::string>& needles) {
  EXPECT_EQ(result.exit_code, 1) << result.err;
  EXPECT_TRUE(StringStartsWith(result.err, "ERROR: ")) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1)
      << result.err;
  for (const std::string& needle : needles) {
    EXPECT_NE(result.err.find(needle), std::string::npos)
        << "missing \"" << needle << "\" in: " << result.err;
  }
}

}  // namespace test
}  // namespace colmap_gcn
