#include "controllers/pair_export.h"

#include <gtest/gtest.h>

#include <set>

#include "../retrieval/retrieval_test_utils.h"
#include "pairing/pairs_io.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

class PairExport : public testing::Test {
 protected:
  void SetUp() override {
    database_path_ = JoinPaths(dir_.Path(), "database.db");
    test::CreateRandomDescriptorDatabase(database_path_, 5, 40, 4, 20, "img");
  }

  std::vector<std::vector<std::string>> Lines(const std::string& path) {
    std::vector<std::vector<std::string>> lines;
    for (const std::string& line : StringSplit(ReadTextFile(path), "\n")) {
      if (!line.empty()) lines.push_back(StringSplit(line, " "));
    }
    return lines;
  }

  TemporaryDirectory dir_{"colmap_gcn_pair_export"};
  std::string database_path_;
};

// hloc's parse_retrieval unpacks exactly `query db` per line.
TEST_F(PairExport, HlocLayoutHasTwoNamesPerLineAndEveryPairOnce) {
  GcnMatchingOptions options;
  options.pairing = "exhaustive";
  PairExportOptions export_options;
  export_options.output_path = JoinPaths(dir_.Path(), "pairs-hloc.txt");
  EXPECT_EQ(ExportPairs(database_path_, options, export_options), 10u);
  std::set<std::pair<std::string, std::string>> pairs;
  for (const auto& line : Lines(export_options.output_path)) {
    ASSERT_EQ(line.size(), 2u);
    EXPECT_NE(line[0], line[1]);
    pairs.insert(std::minmax(line[0], line[1]));
  }
  EXPECT_EQ(pairs.size(), 10u);
}

// The same pairs in COLMAP's layout, readable by matches_importer's parser.
TEST_F(PairExport, ColmapLayoutHoldsTheSamePairs) {
  GcnMatchingOptions options;
  options.pairing = "knn";
  PairExportOptions export_options;
  export_options.output_path = JoinPaths(dir_.Path(), "pairs-hloc.txt");
  const size_t num_pairs = ExportPairs(database_path_, options, export_options);
  export_options.format = PairsFormat::kColmap;
  export_options.output_path = JoinPaths(dir_.Path(), "pairs-colmap.txt");
  EXPECT_EQ(ExportPairs(database_path_, options, export_options), num_pairs);
  const std::vector<ImageNamePair> colmap =
      ReadPairsFile(export_options.output_path);
  const auto hloc = Lines(JoinPaths(dir_.Path(), "pairs-hloc.txt"));
  ASSERT_EQ(colmap.size(), hloc.size());
  ASSERT_GT(num_pairs, 0u);
  for (size_t i = 0; i < colmap.size(); ++i) {
    EXPECT_EQ(colmap[i].first, hloc[i][0]);
    EXPECT_EQ(colmap[i].second, hloc[i][1]);
  }
}

TEST_F(PairExport, RefusesGeneratorsThatNeedVerification) {
  for (const std::string pairing :
       {"adaptive", "adaptive_recall", "graphmatch"}) {
    GcnMatchingOptions options;
    options.pairing = pairing;
    PairExportOptions export_options;
    export_options.output_path = JoinPaths(dir_.Path(), "pairs.txt");
    test::ExpectErrorContaining(
        [&] { ExportPairs(database_path_, options, export_options); },
        "--GcnMatching.pairing " + pairing +
            " chooses pairs from COLMAP's verification");
    EXPECT_FALSE(ExistsFile(export_options.output_path));
  }
}

TEST(WriteHlocPairsFile, RejectsUnknownIdsAndNamesWithSpaces) {
  TemporaryDirectory dir("colmap_gcn_hloc_pairs");
  const std::string path = JoinPaths(dir.Path(), "pairs.txt");
  std::vector<DatabaseImage> images(2);
  images[0].image_id = 1;
  images[0].name = "a.jpg";
  images[1].image_id = 2;
  images[1].name = "b c.jpg";
  test::ExpectErrorContaining(
      [&] {
        WriteHlocPairsFile(path, {{1, 3}}, images);
      },
      "names an image id not in the database");
  test::ExpectErrorContaining(
      [&] {
        WriteHlocPairsFile(path, {{1, 2}}, images);
      },
      "white space");
  EXPECT_FALSE(ExistsFile(path));
}

}  // namespace
}  // namespace colmap_gcn
