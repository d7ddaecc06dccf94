#include "util/option_manager.h"

#include <gtest/gtest.h>

#include "util/error.h"

namespace colmap_gcn {
namespace {

// argv as COLMAP commands see it: argv[0] is the command name.
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

}  // namespace
}  // namespace colmap_gcn
