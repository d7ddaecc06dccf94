// `cmake --install` of this build tree into a temporary prefix: the front
// end beside (not over) COLMAP's bin/colmap, the model, demo and docs in
// their standard places, and the installed front end finding the installed
// model.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "retrieval_test_utils.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

using test::RunShell;

TEST(Install, PutsFilesInStandardPlacesAndFindsTheInstalledModel) {
  TemporaryDirectory dir("colmap_gcn_install");
  const std::string prefix = JoinPaths(dir.Path(), "usr");
  std::string output;
  ASSERT_EQ(RunShell(ShellQuote(COLMAP_GCN_CMAKE_COMMAND) + " --install " +
                         ShellQuote(COLMAP_GCN_BINARY_DIR) + " --prefix " +
                         ShellQuote(prefix),
                     &output),
            0)
      << output;
  const std::string frontend = JoinPaths(prefix, "lib/colmap-gcn/colmap");
  EXPECT_TRUE(ExistsFile(frontend));
  // The command is a relative link, so the prefix can move (DESTDIR, .deb).
  const std::filesystem::path link = JoinPaths(prefix, "bin/colmap-gcn");
  ASSERT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_EQ(std::filesystem::read_symlink(link).string(),
            "../lib/colmap-gcn/colmap");
  // COLMAP's own bin/colmap is not ours to install.
  EXPECT_FALSE(ExistsFile(JoinPaths(prefix, "bin/colmap")));
  for (const char* file : {"share/colmap-gcn/default.gcnmodel",
                           "share/colmap-gcn/demo.sh",
                           "share/doc/colmap-gcn/README.md",
                           "share/doc/colmap-gcn/docs/usage.md",
                           "share/doc/colmap-gcn/docs/install.md"}) {
    EXPECT_TRUE(ExistsFile(JoinPaths(prefix, file))) << file;
  }

  ASSERT_EQ(RunShell(ShellQuote(link.string()) + " gcn_matcher -h", &output), 0)
      << output;
  EXPECT_NE(output.find("Usage: colmap gcn_matcher"), std::string::npos);

  // The default model is the installed one, not the source tree's.
  const std::string database = JoinPaths(dir.Path(), "database.db");
  std::vector<std::pair<std::string, FeatureDescriptors>> images;
  for (int i = 0; i < 4; ++i) {
    images.emplace_back("image" + std::to_string(i) + ".jpg",
                        test::RandomDescriptors(60, 4, 40 + i));
  }
  test::CreateDescriptorDatabase(database, images);
  ASSERT_EQ(
      RunShell("env -u COLMAP_GCN_MODEL " + ShellQuote(link.string()) +
                   " gcn_pair_exporter --database_path " +
                   ShellQuote(database) + " --output_path " +
                   ShellQuote(JoinPaths(dir.Path(), "pairs.txt")) + " 2>&1",
               &output),
      0)
      << output;
  EXPECT_NE(output.find("GCN model " +
                        JoinPaths(prefix, "share/colmap-gcn/default.gcnmodel")),
            std::string::npos)
      << output;
}

}  // namespace
}  // namespace colmap_gcn
