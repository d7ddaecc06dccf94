#include "util/project_file.h"

#include <gtest/gtest.h>

#include <fstream>

#include "test_utils.h"
#include "util/error.h"
#include "util/option_manager.h"

namespace colmap_gcn {
namespace {

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + "/project_file_" + name;
  std::ofstream(path) << text;
  return path;
}

using test::Argv;

TEST(ProjectFile, ReadsColmapLayout) {
  const std::string path = WriteFile("layout.ini",
                                     "# comment\n"
                                     "database_path=/d.db\n"
                                     "\n"
                                     "[GcnMatching]\n"
                                     "k1 = 20\n"
                                     "pairs_path=\n"
                                     "; comment\n"
                                     "[ SiftMatching ]\n"
                                     "max_ratio=0.7\n");
  const std::vector<ProjectFileOption> options = ReadProjectFile(path);
  ASSERT_EQ(options.size(), 4u);
  EXPECT_EQ(options[0].name, "database_path");
  EXPECT_EQ(options[0].value, "/d.db");
  EXPECT_EQ(options[1].name, "GcnMatching.k1");
  EXPECT_EQ(options[1].value, "20");
  EXPECT_EQ(options[1].line, 5);
  EXPECT_EQ(options[2].name, "GcnMatching.pairs_path");
  EXPECT_EQ(options[2].value, "");
  EXPECT_EQ(options[3].name, "SiftMatching.max_ratio");
}

TEST(ProjectFile, MalformedLinesAndMissingFilesNameTheProblem) {
  test::ExpectErrorContaining(
      [&] { ReadProjectFile(WriteFile("bad.ini", "[A]\njust words\n")); },
      "bad.ini:2: expected key=value, got just words");
  test::ExpectErrorContaining(
      [&] { ReadProjectFile(WriteFile("header.ini", "[A\nk=1\n")); },
      "header.ini:1: malformed section header [A");
  test::ExpectErrorContaining([&] { ReadProjectFile("/nonexistent/p.ini"); },
                              "cannot read the project file");
}

TEST(ProjectFile, FindArgumentReadsBothSpellings) {
  EXPECT_EQ(
      FindArgument({"--a", "1", "--project_path", "p.ini"}, "project_path"),
      "p.ini");
  EXPECT_EQ(FindArgument({"--project_path=q.ini"}, "project_path"), "q.ini");
  EXPECT_EQ(FindArgument({"--project_pathx", "r"}, "project_path"), "");
}

// Options come from the file unless the command line gives them; keys under
// a pass-through prefix are passed on like command-line ones.
TEST(ProjectFile, OptionManagerReadsItAndTheCommandLineWins) {
  const std::string path = WriteFile("manager.ini",
                                     "database_path=file.db\n"
                                     "[GcnMatching]\n"
                                     "k1=20\n"
                                     "k2=7\n"
                                     "[SiftMatching]\n"
                                     "max_ratio=0.7\n");
  std::string database_path;
  int k1 = 100;
  int k2 = 5;
  OptionManager manager("test", "summary");
  manager.AddRequiredOption("database_path", &database_path);
  manager.AddDefaultOption("GcnMatching.k1", &k1);
  manager.AddDefaultOption("GcnMatching.k2", &k2);
  manager.AddPassThroughPrefix("SiftMatching.");
  Argv args({"test", "--project_path", path, "--GcnMatching.k2", "9"});
  ASSERT_TRUE(manager.Parse(args.argc(), args.argv()));
  EXPECT_EQ(database_path, "file.db");
  EXPECT_EQ(k1, 20);
  EXPECT_EQ(k2, 9);
  EXPECT_EQ(manager.PassThroughArguments(),
            (std::vector<std::string>{"--SiftMatching.max_ratio", "0.7"}));
  EXPECT_TRUE(manager.Help().find("--project_path") != std::string::npos);
}

TEST(ProjectFile, OptionManagerRejectsUnknownKeysWithTheirLine) {
  const std::string path =
      WriteFile("unknown.ini", "[GcnMatching]\nk1=20\nkk2=3\n");
  int k1 = 100;
  OptionManager manager("test", "summary");
  manager.AddDefaultOption("GcnMatching.k1", &k1);
  manager.AddPassThroughPrefix("SiftMatching.");
  Argv args({"test", "--project_path=" + path});
  test::ExpectErrorContaining(
      [&] { manager.Parse(args.argc(), args.argv()); },
      "unknown.ini:3: unknown option GcnMatching.kk2 for colmap test");
  // A section of another COLMAP command is unknown here too, as in COLMAP.
  const std::string mapper = WriteFile("mapper.ini", "[Mapper]\nx=1\n");
  Argv mapper_args({"test", "--project_path", mapper});
  test::ExpectErrorContaining(
      [&] { manager.Parse(mapper_args.argc(), mapper_args.argv()); },
      "mapper.ini:2: unknown option Mapper.x");
}

}  // namespace
}  // namespace colmap_gcn
