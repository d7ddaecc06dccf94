#include "controllers/incremental_mapping.h"

#include <gtest/gtest.h>

#include "fake_colmap.h"
#include "scene/reconstruction_stats.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using test::ExpectErrorContaining;
using test::FakeColmap;
using Arguments = std::vector<std::string>;

TEST(IncrementalMapping, PassesColmapsDefaultsUnlessTheUserSetsThem) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  const std::string output_path = JoinPaths(dir.Path(), "sparse");
  IncrementalMappingOptions options;
  options.image_path = "/images";
  const IncrementalMappingSummary summary =
      RunIncrementalMapping(fake.Runner(), "/db", output_path, options);
  EXPECT_EQ(fake.LastArguments(),
            (Arguments{"mapper",
                       "--database_path",
                       "/db",
                       "--image_path",
                       "/images",
                       "--output_path",
                       output_path + ".partial",
                       "--Mapper.num_threads",
                       "-1",
                       "--Mapper.min_model_size",
                       "10"}));
  EXPECT_EQ(summary.model_paths, Arguments{JoinPaths(output_path, "0")});
  // The models were moved out of the mapper's scratch folder.
  EXPECT_FALSE(ExistsDir(output_path + ".partial"));

  // Ours (the command binds the user's --Mapper.num_threads and
  // --Mapper.min_model_size to them), then the user's others.
  options.num_threads = 2;
  options.min_model_size = 3;
  options.replace_models = true;
  options.colmap_args = {"--Mapper.ba_refine_focal_length", "0"};
  RunIncrementalMapping(fake.Runner(), "/db", output_path, options);
  EXPECT_EQ(fake.LastArguments(),
            (Arguments{"mapper",
                       "--database_path",
                       "/db",
                       "--image_path",
                       "/images",
                       "--output_path",
                       output_path + ".partial",
                       "--Mapper.num_threads",
                       "2",
                       "--Mapper.min_model_size",
                       "3",
                       "--Mapper.ba_refine_focal_length",
                       "0"}));
}

TEST(IncrementalMapping, RefusesOrReplacesEarlierModels) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  const std::string output_path = JoinPaths(dir.Path(), "sparse");
  CreateDirIfNotExists(JoinPaths(output_path, "0"));
  CreateDirIfNotExists(JoinPaths(output_path, "1"));
  IncrementalMappingOptions options;
  options.image_path = "/images";
  ExpectErrorContaining(
      [&] {
        RunIncrementalMapping(fake.Runner(), "/db", output_path, options);
      },
      output_path + " already holds models");
  EXPECT_TRUE(fake.LastArguments().empty());  // COLMAP never ran

  // Replacing: only this run's model remains.
  options.replace_models = true;
  EXPECT_EQ(RunIncrementalMapping(fake.Runner(), "/db", output_path, options)
                .model_paths,
            Arguments{JoinPaths(output_path, "0")});
  EXPECT_FALSE(ExistsDir(JoinPaths(output_path, "1")));
}

TEST(IncrementalMapping, ColmapFailureIsAnError) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  fake.FailRuns();
  IncrementalMappingOptions options;
  options.image_path = "/images";
  ExpectErrorContaining(
      [&] {
        RunIncrementalMapping(
            fake.Runner(), "/db", JoinPaths(dir.Path(), "sparse"), options);
      },
      "mapper");
}

TEST(IncrementalMapping, UnreadableModelIsAnErrorAndNotKept) {
  TemporaryDirectory dir;
  const FakeColmap fake(dir.Path());
  fake.WriteTruncatedModels();
  const std::string output_path = JoinPaths(dir.Path(), "sparse");
  IncrementalMappingOptions options;
  options.image_path = "/images";
  ExpectErrorContaining(
      [&] {
        RunIncrementalMapping(fake.Runner(), "/db", output_path, options);
      },
      "colmap mapper exited 0 but wrote an unreadable model (");
  EXPECT_TRUE(ListSparseModels(output_path).empty());
  EXPECT_FALSE(ExistsDir(output_path + ".partial"));
}

TEST(IncrementalMapping, CheckNamesTheField) {
  IncrementalMappingOptions options;
  ExpectErrorContaining([&] { options.Check(); }, "image_path");
  options.image_path = "/images";
  options.num_threads = 0;
  ExpectErrorContaining([&] { options.Check(); }, "num_threads");
  options.num_threads = 1;
  options.min_model_size = -1;
  ExpectErrorContaining([&] { options.Check(); }, "min_model_size");
}

}  // namespace
}  // namespace colmap_gcn
