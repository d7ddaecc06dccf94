#include "util/option_manager.h"

#include <gtest/gtest.h>

#include "test_utils.h"
#include "util/error.h"

namespace colmap_gcn {
namespace {

using test::Argv;

TEST(OptionManager, ParsesRequiredDefaultAndPassThrough) {
  std::string database_path;
  int k1 = 100;
  bool verbose = false;
  OptionManager manager("test", "summary");
  manager.AddRequiredOption("database_path", &database_path);
  manager.AddDefaultOption("GcnMatching.k1", &k1);
  manager.AddDefaultOption("GcnMatching.verbose", &verbose);
  manager.AddPassThroughPrefix("SiftMatching.");
  Argv args({"test",
             "--database_path",
             "d.db",
             "--SiftMatching.max_ratio",
             "0.7",
             "--GcnMatching.k1=20",
             "--SiftMatching.use_gpu=0"});
  ASSERT_TRUE(manager.Parse(args.argc(), args.argv()));
  EXPECT_EQ(database_path, "d.db");
  EXPECT_EQ(k1, 20);
  EXPECT_FALSE(verbose);
  EXPECT_EQ(
      manager.PassThroughArguments(),
      (std::vector<std::string>{
          "--SiftMatching.max_ratio", "0.7", "--SiftMatching.use_gpu=0"}));
}

// A COLMAP option the command reads itself is parsed, typed and checked
// once, and not passed through (so never passed to COLMAP twice).
TEST(OptionManager, BoundOptionUnderAPassThroughPrefixIsOurs) {
  int min_num_inliers = 15;
  int num_threads = 1;
  OptionManager manager("test", "summary");
  manager.AddDefaultOption("SiftMatching.min_num_inliers", &min_num_inliers);
  manager.AddDefaultOption("Benchmark.mapper_num_threads", &num_threads);
  manager.AddAliasOption("Mapper.num_threads", &num_threads);
  manager.AddPassThroughPrefix("SiftMatching.");
  manager.AddPassThroughPrefix("Mapper.");
  Argv args({"test",
             "--SiftMatching.max_ratio",
             "0.7",
             "--SiftMatching.min_num_inliers",
             "30",
             "--Mapper.num_threads=4",
             "--Mapper.ba_refine_focal_length",
             "0"});
  ASSERT_TRUE(manager.Parse(args.argc(), args.argv()));
  EXPECT_EQ(min_num_inliers, 30);
  EXPECT_EQ(num_threads, 4);
  EXPECT_EQ(manager.PassThroughArguments(),
            (std::vector<std::string>{"--SiftMatching.max_ratio",
                                      "0.7",
                                      "--Mapper.ba_refine_focal_length",
                                      "0"}));
  // Not given: the alias leaves the field to the other flag.
  Argv other({"test", "--Benchmark.mapper_num_threads", "2"});
  ASSERT_TRUE(manager.Parse(other.argc(), other.argv()));
  EXPECT_EQ(num_threads, 2);
  Argv text({"test", "--SiftMatching.min_num_inliers", "abc"});
  EXPECT_THROW(manager.Parse(text.argc(), text.argv()), Error);
}

TEST(OptionManager, HelpReturnsFalse) {
  std::string database_path;
  OptionManager manager("test", "summary");
  manager.AddRequiredOption("database_path", &database_path);
  Argv args({"test", "-h"});
  testing::internal::CaptureStdout();
  EXPECT_FALSE(manager.Parse(args.argc(), args.argv()));
  const std::string help = testing::internal::GetCapturedStdout();
  EXPECT_NE(help.find("--database_path"), std::string::npos);
}

TEST(OptionManager, RejectsUnknownMissingAndMalformed) {
  std::string database_path;
  int k1 = 100;
  OptionManager manager("test", "summary");
  manager.AddRequiredOption("database_path", &database_path);
  manager.AddDefaultOption("GcnMatching.k1", &k1);
  Argv unknown({"test", "--database_path", "d", "--nope", "1"});
  EXPECT_THROW(manager.Parse(unknown.argc(), unknown.argv()), Error);
  Argv missing({"test", "--GcnMatching.k1", "3"});
  EXPECT_THROW(manager.Parse(missing.argc(), missing.argv()), Error);
  Argv malformed({"test", "--database_path", "d", "--GcnMatching.k1", "x"});
  EXPECT_THROW(manager.Parse(malformed.argc(), malformed.argv()), Error);
}

enum class Color { kRed, kDarkBlue };
const EnumNames<Color> kColorNames = {{"red", Color::kRed},
                                      {"dark_blue", Color::kDarkBlue}};

TEST(OptionManager, EnumOptionsParseOnceFromTheirNames) {
  Color color = Color::kRed;
  OptionManager manager("test", "summary");
  manager.AddEnumOption("Paint.color", &color, kColorNames, "the colour");
  Argv defaults({"test"});
  ASSERT_TRUE(manager.Parse(defaults.argc(), defaults.argv()));
  EXPECT_EQ(color, Color::kRed);
  Argv given({"test", "--Paint.color", "dark_blue"});
  ASSERT_TRUE(manager.Parse(given.argc(), given.argv()));
  EXPECT_EQ(color, Color::kDarkBlue);
  EXPECT_TRUE(manager.IsGiven("Paint.color"));
  EXPECT_EQ(manager.GivenValue("Paint.color"), "dark_blue");
  EXPECT_EQ(manager.FlagName(&color), "--Paint.color");
  // The help lists the choices and shows the default's name.
  EXPECT_NE(manager.Help().find("red|dark_blue"), std::string::npos);
  Argv bad({"test", "--Paint.color", "green"});
  try {
    manager.Parse(bad.argc(), bad.argv());
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()),
              "--Paint.color must be one of red|dark_blue (got \"green\")");
  }
}

TEST(OptionManager, OneFlagBoundToSeveralFields) {
  int knn_k = 25;
  int tree_k = 30;
  OptionManager manager("test", "summary");
  manager.AddDefaultOption("GcnMatching.k", &knn_k, "neighbours");
  manager.AddDefaultOption("GcnMatching.k", &tree_k, "ignored help");
  Argv defaults({"test"});
  ASSERT_TRUE(manager.Parse(defaults.argc(), defaults.argv()));
  // Unset, each field keeps its own default.
  EXPECT_EQ(knn_k, 25);
  EXPECT_EQ(tree_k, 30);
  EXPECT_FALSE(manager.IsGiven("GcnMatching.k"));
  Argv given({"test", "--GcnMatching.k=7"});
  ASSERT_TRUE(manager.Parse(given.argc(), given.argv()));
  EXPECT_EQ(knn_k, 7);
  EXPECT_EQ(tree_k, 7);
  EXPECT_EQ(manager.FlagName(&tree_k), "--GcnMatching.k");
  EXPECT_EQ(manager.GivenValue("GcnMatching.k"), "7");
}

}  // namespace
}  // namespace colmap_gcn

namespace colmap_gcn {
namespace {

TEST(ArgumentsWithPrefix, SelectsOptionsWithTheirValues) {
  const std::vector<std::string> args = {"--SiftMatching.max_ratio",
                                         "0.7",
                                         "--Mapper.num_threads=1",
                                         "--ImageReader.single_camera",
                                         "1",
                                         "--SiftExtraction.use_gpu",
                                         "0"};
  EXPECT_EQ(ArgumentsWithPrefix(args, {"SiftMatching."}),
            (std::vector<std::string>{"--SiftMatching.max_ratio", "0.7"}));
  EXPECT_EQ(ArgumentsWithPrefix(args, {"Mapper."}),
            (std::vector<std::string>{"--Mapper.num_threads=1"}));
  EXPECT_EQ(ArgumentsWithPrefix(args, {"ImageReader.", "SiftExtraction."}),
            (std::vector<std::string>{"--ImageReader.single_camera",
                                      "1",
                                      "--SiftExtraction.use_gpu",
                                      "0"}));
  EXPECT_TRUE(ArgumentsWithPrefix(args, {"GcnMatching."}).empty());
}

// -h shows defaults as typed, not with binary rounding noise.
TEST(OptionManager, HelpShowsShortestFloatingPointDefaults) {
  double fraction = 0.1;
  float ratio = 0.8f;
  OptionManager manager("test", "summary");
  manager.AddDefaultOption("GcnMatching.fraction", &fraction);
  manager.AddDefaultOption("GcnMatching.ratio", &ratio);
  const std::string help = manager.Help();
  EXPECT_NE(help.find("--GcnMatching.fraction arg (=0.1)"), std::string::npos)
      << help;
  EXPECT_NE(help.find("--GcnMatching.ratio arg (=0.8)"), std::string::npos)
      << help;
}

}  // namespace
}  // namespace colmap_gcn
