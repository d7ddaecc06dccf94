#include "pairing/sequential_pairing.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "util/option_check.h"

namespace colmap_gcn {
namespace {

// Ids unrelated to the name order, as databases have them.
std::vector<DatabaseImage> MakeImages(int num_images) {
  std::vector<DatabaseImage> images;
  for (int i = 0; i < num_images; ++i) {
    DatabaseImage image;
    image.image_id = static_cast<image_t>(100 - 3 * i);
    char name[32];
    std::snprintf(name, sizeof(name), "frame%03d.jpg", num_images - 1 - i);
    image.name = name;
    images.push_back(image);
  }
  return images;
}

// Position in name order of each image id.
std::vector<std::pair<int, int>> Positions(
    const std::vector<DatabaseImage>& images,
    const std::vector<ImagePair>& pairs) {
  std::vector<std::pair<int, int>> positions;
  for (const auto& [a, b] : pairs) {
    int pa = -1, pb = -1;
    for (const DatabaseImage& image : images) {
      const int position = std::stoi(image.name.substr(5, 3));
      if (image.image_id == a) pa = position;
      if (image.image_id == b) pb = position;
    }
    positions.emplace_back(pa, pb);
  }
  return positions;
}

TEST(SequentialPairGenerator, PairsEachImageWithTheNextOverlapInNameOrder) {
  const auto images = MakeImages(6);
  SequentialMatchingOptions options;
  options.overlap = 2;
  SequentialPairGenerator generator(options, images);
  EXPECT_EQ(Positions(images, generator.AllPairs()),
            (std::vector<std::pair<int, int>>{{0, 1},
                                              {0, 2},
                                              {1, 2},
                                              {1, 3},
                                              {2, 3},
                                              {2, 4},
                                              {3, 4},
                                              {3, 5},
                                              {4, 5}}));
}

TEST(SequentialPairGenerator, DefaultOverlapIsColmapsAndCapsAtTheEnd) {
  EXPECT_EQ(SequentialMatchingOptions().overlap, 10);
  // Fewer images than the overlap: every pair, once.
  const auto images = MakeImages(5);
  SequentialPairGenerator generator(SequentialMatchingOptions(), images);
  EXPECT_EQ(generator.AllPairs().size(), 10u);
}

TEST(SequentialPairGenerator, QuadraticOverlapAddsPowersOfTwo) {
  const auto images = MakeImages(20);
  SequentialMatchingOptions options;
  options.overlap = 3;
  options.quadratic_overlap = true;
  SequentialPairGenerator generator(options, images);
  std::set<std::pair<int, int>> pairs;
  for (const auto& pair : Positions(images, generator.AllPairs())) {
    EXPECT_TRUE(pairs.insert(pair).second) << "twice: " << pair.first;
  }
  // From image 0: linear 1, 2, 3; powers 1, 2, 4 add only 4.
  EXPECT_TRUE(pairs.count({0, 3}));
  EXPECT_TRUE(pairs.count({0, 4}));
  EXPECT_FALSE(pairs.count({0, 5}));
  EXPECT_FALSE(pairs.count({0, 8}));
  // Linear 3 per image up to the end, plus one 4-step per image that has one.
  EXPECT_EQ(pairs.size(), (17u * 3 + 2 + 1) + 16u);
}

TEST(SequentialPairGenerator, BlocksAndReset) {
  const auto images = MakeImages(12);
  SequentialMatchingOptions options;
  options.block_size = 4;
  SequentialPairGenerator generator(options, images);
  const std::vector<ImagePair> all = generator.AllPairs();
  generator.Reset();
  std::vector<ImagePair> blocks;
  while (!generator.HasFinished()) {
    const auto block = generator.Next();
    EXPECT_LE(block.size(), 4u);
    blocks.insert(blocks.end(), block.begin(), block.end());
  }
  EXPECT_EQ(blocks, all);
  EXPECT_EQ(all.size(), 65u);  // 12 images, overlap 10: all 66 but (0, 11)
}

TEST(SequentialPairGenerator, RejectsBadOverlap) {
  SequentialMatchingOptions options;
  options.overlap = 0;
  EXPECT_THROW(SequentialPairGenerator(options, MakeImages(3)), OptionError);
}

}  // namespace
}  // namespace colmap_gcn
