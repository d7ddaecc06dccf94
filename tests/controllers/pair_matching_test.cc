#include "controllers/pair_matching.h"

#include <gtest/gtest.h>

#include "fake_colmap.h"
#include "scene/database.h"
#include "scene/database_copy.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using test::ExpectErrorContaining;
using test::FakeColmap;

// A database of four images, as the fake's feature_extractor writes it.
std::string FourImageDatabase(const TemporaryDirectory& dir,
                              const FakeColmap& fake) {
  fake.SetExtractedImages(4);
  const std::string path = JoinPaths(dir.Path(), "database.db");
  CopyDatabase(JoinPaths(dir.Path(), "template.db"), path);
  return path;
}

// COLMAP 3.8 logs a failed SQLite write and exits 0: the block must be
// found missing in the copy, the database left as it was, and no success
// reported.
TEST(MatchImagePairs, ColmapExitingZeroWithoutItsMatchesIsAnError) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  const std::string database_path = FourImageDatabase(dir, fake);
  const std::string before = ReadTextFile(database_path);
  fake.SkipWrites();
  PairMatchingOptions options;
  options.pairs_path = JoinPaths(dir.Path(), "pairs.txt");
  ExpectErrorContaining(
      [&] {
        MatchImagePairs(
            fake.Runner(), database_path, {{1, 2}, {3, 4}}, options);
      },
      "colmap matches_importer exited 0 but wrote no result for 2 of the 2 "
      "pairs it was given (the first: img1.jpg img2.jpg) -- " +
          database_path + " is unchanged");
  EXPECT_EQ(ReadTextFile(database_path), before);
  // What COLMAP may have written stays for the next run to resume.
  EXPECT_TRUE(ExistsFile(database_path + ".gcn-partial"));
}

TEST(MatchImagePairs, ColmapReportingAFullDiskIsAnErrorNamingIt) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  const std::string database_path = FourImageDatabase(dir, fake);
  const std::string before = ReadTextFile(database_path);
  fake.PrintOnEveryRun(
      "SQLite error [/build/colmap/src/base/database.cc, line 1092]: "
      "database or disk is full\n");
  PairMatchingOptions options;
  options.pairs_path = JoinPaths(dir.Path(), "pairs.txt");
  ExpectErrorContaining(
      [&] {
        MatchImagePairs(fake.Runner(), database_path, {{1, 2}}, options);
      },
      "colmap matches_importer reported the disk is full (SQLite: database "
      "or disk is full) although it exited 0");
  EXPECT_EQ(ReadTextFile(database_path), before);
}

TEST(MatchImagePairs, BlocksAreATenthOfThePairsForProgress) {
  // At least 100 pairs per COLMAP run, at most the block size.
  EXPECT_EQ(ProgressBlockSize(50, 1225), 100u);
  EXPECT_EQ(ProgressBlockSize(877, 1225), 100u);
  EXPECT_EQ(ProgressBlockSize(3160, 1225), 316u);
  EXPECT_EQ(ProgressBlockSize(100000, 1225), 1225u);
  // A block size the user chose below 100 wins.
  EXPECT_EQ(ProgressBlockSize(877, 10), 10u);
}

}  // namespace
}  // namespace colmap_gcn
