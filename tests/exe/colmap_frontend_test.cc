#include <gtest/gtest.h>

#include <fstream>

#include "controllers/pair_generators.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

using test::FrontendExe;
using test::RealColmapExe;
using test::RunShell;

// Runs our front end with a PATH that holds the build's bin dir first, as
// users set it up.
int RunFrontend(const std::string& args,
                std::string* output,
                const std::string& env = "") {
  const std::string bin_dir =
      FrontendExe().substr(0, FrontendExe().find_last_of('/'));
  return RunShell(env + " PATH=" + ShellQuote(bin_dir) + ":$PATH " +
                      ShellQuote(FrontendExe()) + " " + args,
                  output);
}

size_t CountLines(const std::string& text) {
  return StringSplit(StringTrim(text), "\n").size();
}

TEST(ColmapFrontend, HelpListsColmapAndOurCommands) {
  if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
  std::string output;
  EXPECT_EQ(RunFrontend("help", &output), 0);
  EXPECT_NE(output.find("COLMAP 3."), std::string::npos) << output;
  EXPECT_NE(output.find("gcn_matcher"), std::string::npos) << output;
  EXPECT_NE(output.find("mapper"), std::string::npos) << output;
}

TEST(ColmapFrontend, PassesOtherCommandsThroughWithExitCode) {
  if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
  TemporaryDirectory dir;
  const std::string args =
      "model_analyzer --path " + ShellQuote(JoinPaths(dir.Path(), "none"));
  std::string ours;
  std::string real;
  const int our_code = RunFrontend(args, &ours);
  const int real_code =
      RunShell(ShellQuote(RealColmapExe()) + " " + args, &real);
  EXPECT_NE(real_code, 0);
  EXPECT_EQ(our_code, real_code);
  // Same message (COLMAP's log lines carry timestamps, so compare the text).
  EXPECT_NE(real.find("do not exist"), std::string::npos) << real;
  EXPECT_NE(ours.find("do not exist"), std::string::npos) << ours;

  // A command COLMAP does not know either: COLMAP's own answer and code.
  EXPECT_EQ(RunFrontend("no_such_command", &ours),
            RunShell(ShellQuote(RealColmapExe()) + " no_such_command", &real));
  EXPECT_EQ(ours, real);
}

TEST(ColmapFrontend, GcnMatcherHelpAndBadOptions) {
  std::string output;
  EXPECT_EQ(RunFrontend("gcn_matcher -h", &output), 0);
  EXPECT_NE(output.find("--database_path"), std::string::npos);
  EXPECT_NE(output.find("--GcnMatching.pairing"), std::string::npos);

  EXPECT_EQ(RunFrontend("gcn_matcher --GcnMatching.nope 1", &output), 1);
  EXPECT_EQ(CountLines(output), 1u) << output;
  EXPECT_TRUE(StringStartsWith(output, "ERROR: ")) << output;
}

TEST(ColmapFrontend, BenchmarkHelpListsEveryRegisteredMethod) {
  std::string output;
  EXPECT_EQ(RunFrontend("gcn_benchmark -h", &output), 0);
  // The --methods entry runs up to the next flag; help wraps lines, so
  // whitespace is collapsed before looking for "name:<k>".
  const size_t begin = output.find("--methods");
  ASSERT_NE(begin, std::string::npos) << output;
  const size_t end = output.find("--", begin + 2);
  std::string methods_help;
  for (const std::string& word :
       StringSplit(output.substr(begin, end - begin), " \n")) {
    if (!word.empty()) methods_help += word + " ";
  }
  const PairGeneratorRegistry& registry = PairGenerators();
  for (const std::string& name : registry.Names()) {
    if (!registry.IsBenchmarkMethod(name)) continue;
    const std::string syntax = registry.TakesDepth(name) ? name + ":<k>" : name;
    EXPECT_NE(methods_help.find(" " + syntax + " "), std::string::npos)
        << syntax << " missing from: " << methods_help;
  }
  EXPECT_NE(methods_help.find(" oracle "), std::string::npos) << methods_help;
  EXPECT_NE(methods_help.find(" none"), std::string::npos) << methods_help;
}

TEST(ColmapFrontend, MissingDatabaseIsOneLineErrorAndNotCreated) {
  TemporaryDirectory dir;
  const std::string database_path = JoinPaths(dir.Path(), "missing.db");
  std::string output;
  EXPECT_EQ(
      RunFrontend("gcn_matcher --database_path " + database_path, &output), 1);
  EXPECT_EQ(CountLines(output), 1u) << output;
  EXPECT_NE(output.find(database_path), std::string::npos) << output;
  EXPECT_FALSE(ExistsFile(database_path));
}

TEST(ColmapFrontend, NonColmapSqliteIsOneLineErrorAndUntouched) {
  TemporaryDirectory dir;
  const std::string database_path = JoinPaths(dir.Path(), "other.db");
  ASSERT_EQ(RunShell("sqlite3 " + database_path +
                     " 'CREATE TABLE notes(id INTEGER, body TEXT);"
                     " INSERT INTO notes VALUES (1, \"hello\");'"),
            0);
  const std::string before = ReadTextFile(database_path);
  std::string output;
  EXPECT_EQ(
      RunFrontend("gcn_matcher --database_path " + database_path, &output), 1);
  EXPECT_EQ(CountLines(output), 1u) << output;
  EXPECT_EQ(ReadTextFile(database_path), before);

  const std::string text_path = JoinPaths(dir.Path(), "text.db");
  WriteFileAtomically(text_path, "not a database at all\n");
  EXPECT_EQ(RunFrontend("gcn_matcher --database_path " + text_path, &output),
            1);
  EXPECT_EQ(CountLines(output), 1u) << output;
  EXPECT_EQ(ReadTextFile(text_path), "not a database at all\n");
}

TEST(ColmapFrontend, MissingColmapIsOneLineErrorAndNeverItself) {
  std::string output;
  // Only our front end on PATH: it must not run itself as "the real COLMAP".
  const std::string bin_dir =
      FrontendExe().substr(0, FrontendExe().find_last_of('/'));
  EXPECT_EQ(RunShell("env -u COLMAP_EXE PATH=" + ShellQuote(bin_dir) + " " +
                         ShellQuote(FrontendExe()) + " mapper -h",
                     &output),
            1);
  EXPECT_EQ(CountLines(output), 1u) << output;
  EXPECT_NE(output.find("COLMAP not found"), std::string::npos) << output;

  EXPECT_EQ(
      RunFrontend(
          "feature_extractor -h", &output, "COLMAP_EXE=/nonexistent/colmap"),
      1);
  EXPECT_EQ(CountLines(output), 1u) << output;
}

}  // namespace
}  // namespace colmap_gcn
