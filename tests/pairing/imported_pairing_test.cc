#include "pairing/imported_pairing.h"

#include <gtest/gtest.h>

#include <set>

#include "pairing/pairing_test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using test::MakeImages;

TEST(ImportedPairGenerator, ResolvesNamesAndDropsDuplicates) {
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "pairs.txt");
  WriteFileAtomically(path,
                      "# comment\n"
                      "img1.jpg img2.jpg\n"
                      "img2.jpg img1.jpg\n"
                      "img1.jpg img1.jpg\n"
                      "\n"
                      "img3.jpg img1.jpg 0.9\n"
                      "img1.jpg img2.jpg\n");
  ImagePairsMatchingOptions options;
  options.match_list_path = path;
  options.block_size = 1;
  ImportedPairGenerator generator(options, MakeImages({1, 2, 3}));
  std::vector<ImagePair> pairs;
  while (!generator.HasFinished()) {
    const auto block = generator.Next();
    EXPECT_EQ(block.size(), 1u);
    pairs.insert(pairs.end(), block.begin(), block.end());
  }
  EXPECT_EQ(pairs, (std::vector<ImagePair>{{1, 2}, {3, 1}}));
}

TEST(ImportedPairGenerator, UnknownNamesAreAnErrorNamingThem) {
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "pairs.txt");
  WriteFileAtomically(path, "img1.jpg ghost.jpg\n");
  ImagePairsMatchingOptions options;
  options.match_list_path = path;
  try {
    ImportedPairGenerator generator(options, MakeImages({1, 2}));
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("ghost.jpg"), std::string::npos);
  }
  options.match_list_path = JoinPaths(dir.Path(), "missing.txt");
  EXPECT_THROW(ImportedPairGenerator(options, MakeImages({1, 2})), Error);
}

}  // namespace
}  // namespace colmap_gcn
