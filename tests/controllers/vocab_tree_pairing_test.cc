#include "controllers/vocab_tree_pairing.h"

#include <gtest/gtest.h>

#include "util/error.h"

namespace colmap_gcn {
namespace {

std::vector<DatabaseImage> Images() {
  std::vector<DatabaseImage> images;
  for (image_t id = 1; id <= 4; ++id) {
    DatabaseImage image;
    image.image_id = id;
    image.name = "img " + std::to_string(id) + ".png";  // spaces are fine
    images.push_back(image);
  }
  return images;
}

// As printed by COLMAP 3.8's vocab_tree_retriever (the query is not always
// its own top hit).
const char kOutput[] = R"(Indexing image [1/4] in 0.1s
Querying for image img 1.png [1/4] in 0.107s
  image_id=1, image_name=img 1.png, score=0.416958
  image_id=3, image_name=img 3.png, score=0.343218
  image_id=2, image_name=img 2.png, score=0.262586
Querying for image img 2.png [2/4] in 0.148s
  image_id=3, image_name=img 3.png, score=0.773525
  image_id=2, image_name=img 2.png, score=0.618026
  image_id=1, image_name=img 1.png, score=0.097923
Querying for image img 4.png [4/4] in 0.1s
  image_id=4, image_name=img 4.png, score=0.9
  image_id=1, image_name=img 1.png, score=0.1
  image_id=2, image_name=img 2.png, score=0.05
Elapsed time: 0.010 [minutes]
)";

TEST(ParseVocabTreeRetrieval, DropsTheQueryKeepsKAndDeduplicates) {
  EXPECT_EQ(ParseVocabTreeRetrieval(kOutput, Images(), 2),
            (std::vector<ImagePair>{{1, 3}, {1, 2}, {2, 3}, {4, 1}, {4, 2}}));
  EXPECT_EQ(ParseVocabTreeRetrieval(kOutput, Images(), 1),
            (std::vector<ImagePair>{{1, 3}, {2, 3}, {4, 1}}));
}

TEST(ParseVocabTreeRetrieval, UnknownImagesAreErrors) {
  EXPECT_THROW(ParseVocabTreeRetrieval(
                   "Querying for image ghost.png [1/1] in 0.1s\n", Images(), 2),
               Error);
  EXPECT_THROW(
      ParseVocabTreeRetrieval("Querying for image img 1.png [1/1] in 0.1s\n"
                              "  image_id=9, image_name=x, score=1\n",
                              Images(),
                              2),
      Error);
}

TEST(AutoNumVisualWords, PowerOfTwoBoundedByDescriptors) {
  EXPECT_EQ(AutoNumVisualWords(10), 10);
  EXPECT_EQ(AutoNumVisualWords(1000), 64);
  EXPECT_EQ(AutoNumVisualWords(23852), 256);
  EXPECT_EQ(AutoNumVisualWords(110000), 2048);
  EXPECT_EQ(AutoNumVisualWords(100000000), 16384);
}

}  // namespace
}  // namespace colmap_gcn
