#include "pairing/pairs_io.h"

#include <gtest/gtest.h>

#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

std::vector<DatabaseImage> MakeImages(
    const std::vector<std::pair<image_t, std::string>>& entries) {
  std::vector<DatabaseImage> images;
  for (const auto& [id, name] : entries) {
    DatabaseImage image;
    image.image_id = id;
    image.name = name;
    images.push_back(image);
  }
  return images;
}

TEST(PairsFile, ParsesLikeColmap38) {
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "pairs.txt");
  WriteFileAtomically(path,
                      "# header\n\n"
                      "a.jpg b.jpg\r\n"
                      "sub/c.jpg a.jpg 0.75\n");
  EXPECT_EQ(
      ReadPairsFile(path),
      (std::vector<ImageNamePair>{{"a.jpg", "b.jpg"}, {"sub/c.jpg", "a.jpg"}}));
  // A double space or a tab breaks COLMAP's parser: refuse, don't guess.
  WriteFileAtomically(path, "a.jpg  b.jpg\n");
  EXPECT_THROW(ReadPairsFile(path), Error);
  WriteFileAtomically(path, "a.jpg\tb.jpg\n");
  EXPECT_THROW(ReadPairsFile(path), Error);
}

TEST(PairsFile, WritesNamesAndScoresAndRoundTrips) {
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "pairs.txt");
  const auto images = MakeImages({{4, "x/a.jpg"}, {9, "b.png"}, {2, "c.jpg"}});
  WritePairsFile(path, {{4, 9}, {2, 4}}, images, {0.5f, 0.25f});
  EXPECT_EQ(ReadTextFile(path), "x/a.jpg b.png 0.5\nc.jpg x/a.jpg 0.25\n");
  EXPECT_EQ(
      ReadPairsFile(path),
      (std::vector<ImageNamePair>{{"x/a.jpg", "b.png"}, {"c.jpg", "x/a.jpg"}}));
  WritePairsFile(path, {{9, 2}}, images);
  EXPECT_EQ(ReadTextFile(path), "b.png c.jpg\n");
}

TEST(PairsFile, RefusesNamesColmapCannotParse) {
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "pairs.txt");
  const auto images = MakeImages({{1, "my photo.jpg"}, {2, "b.jpg"}});
  try {
    WritePairsFile(path, {{1, 2}}, images);
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("my photo.jpg"),
              std::string::npos);
  }
  EXPECT_FALSE(ExistsFile(path));
  EXPECT_THROW(WritePairsFile(path, {{1, 3}}, images), Error);
}

// COLMAP 3.8's matches_importer --match_type raw: the names, one
// "idx1 idx2" line per match, an empty line after each pair.
TEST(RawMatchesFile, WritesEachPairsBlockAndRefusesUnknownIds) {
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "matches.txt");
  const auto images = MakeImages({{4, "x/a.jpg"}, {9, "b.png"}});
  FeatureMatches matches(2, 2);
  matches << 0, 7, 12, 3;
  WriteRawMatchesFile(
      path, {{4, 9}, {9, 4}}, {matches, FeatureMatches()}, images);
  EXPECT_EQ(ReadTextFile(path),
            "x/a.jpg b.png\n0 7\n12 3\n\nb.png x/a.jpg\n\n");
  EXPECT_THROW(WriteRawMatchesFile(path, {{4, 5}}, {FeatureMatches()}, images),
               Error);
}

}  // namespace
}  // namespace colmap_gcn
