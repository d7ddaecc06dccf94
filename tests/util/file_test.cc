#include "util/file.h"

#include <gtest/gtest.h>

#include "util/error.h"

namespace colmap_gcn {
namespace {

TEST(File, AtomicWriteReadAndTemporaryDirectory) {
  std::string dir_path;
  {
    TemporaryDirectory dir;
    dir_path = dir.Path();
    ASSERT_TRUE(ExistsDir(dir_path));
    const std::string path = JoinPaths(dir_path, "a.txt");
    WriteFileAtomically(path, "one\n");
    WriteFileAtomically(path, "two\n");
    EXPECT_EQ(ReadTextFile(path), "two\n");
    EXPECT_FALSE(ExistsFile(path + ".tmp"));
    EXPECT_THROW(ReadTextFile(JoinPaths(dir_path, "missing")), Error);
    CreateDirIfNotExists(JoinPaths(dir_path, "x/y"));
    EXPECT_TRUE(ExistsDir(JoinPaths(dir_path, "x/y")));
  }
  EXPECT_FALSE(ExistsDir(dir_path));
}

}  // namespace
}  // namespace colmap_gcn
