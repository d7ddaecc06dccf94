#include "util/option_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "util/option_manager.h"

namespace colmap_gcn {
namespace {

struct ToyOptions {
  int k1 = -1;
  int num_threads = -1;
  double threshold = -1;
  double ratio = 0.5;
  std::string pairing = "gcn";
  std::vector<int> dims = {4, 2};

  void Check() const {
    CHECK_OPTION_UNSET_OR_GE(k1, -1, "the model's value", 1);
    CHECK_OPTION_NUM_THREADS(num_threads);
    CHECK_OPTION_UNSET_OR_RANGE(threshold, -1, "the model's value", 0.0, 1.0);
    CHECK_OPTION_INTERVAL(ratio, 0.0, false, 1.0, true);
    CHECK_OPTION_ONE_OF(pairing, "gcn", "exhaustive");
    CHECK_OPTION(dims, !dims.empty(), "be a non-empty list");
  }
};

std::string CheckMessage(const ToyOptions& options) {
  try {
    options.Check();
  } catch (const OptionError& error) {
    return error.what();
  }
  return "";
}

TEST(OptionCheck, AcceptsValidValuesAndTheUnsetValueExactly) {
  ToyOptions options;
  EXPECT_EQ(CheckMessage(options), "");
  options.k1 = 1;
  options.num_threads = 3;
  options.threshold = 0;
  options.ratio = 1;
  options.pairing = "exhaustive";
  EXPECT_EQ(CheckMessage(options), "");
  options.threshold = 1;
  EXPECT_EQ(CheckMessage(options), "");
}

TEST(OptionCheck, MessagesNameTheFieldTheRequirementAndTheValue) {
  const auto message = [](auto mutate) {
    ToyOptions options;
    mutate(&options);
    return CheckMessage(options);
  };
  EXPECT_EQ(message([](ToyOptions* o) { o->k1 = 0; }),
            "k1 must be -1 (the model's value) or >= 1 (got 0)");
  EXPECT_EQ(message([](ToyOptions* o) { o->k1 = -3; }),
            "k1 must be -1 (the model's value) or >= 1 (got -3)");
  EXPECT_EQ(message([](ToyOptions* o) { o->num_threads = 0; }),
            "num_threads must be -1 (all cores) or >= 1 (got 0)");
  EXPECT_EQ(message([](ToyOptions* o) { o->threshold = 1.5; }),
            "threshold must be -1 (the model's value) or in [0, 1] (got 1.5)");
  EXPECT_EQ(message([](ToyOptions* o) { o->threshold = -0.5; }),
            "threshold must be -1 (the model's value) or in [0, 1] (got "
            "-0.5)");
  EXPECT_EQ(message([](ToyOptions* o) { o->ratio = 0; }),
            "ratio must be in (0, 1] (got 0)");
  EXPECT_EQ(message([](ToyOptions* o) { o->pairing = "foo"; }),
            "pairing must be one of gcn|exhaustive (got \"foo\")");
  EXPECT_EQ(message([](ToyOptions* o) { o->dims.clear(); }),
            "dims must be a non-empty list (got )");
}

TEST(OptionCheck, NanFailsEveryBound) {
  ToyOptions options;
  options.ratio = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(CheckMessage(options), "ratio must be in (0, 1] (got nan)");
}

TEST(OptionCheck, ComparisonsAndVectors) {
  const int zero = 0;
  EXPECT_THROW(CHECK_OPTION_GE(zero, 1), OptionError);
  EXPECT_THROW(CHECK_OPTION_GT(zero, 0), OptionError);
  EXPECT_THROW(CHECK_OPTION_LT(zero, 0), OptionError);
  EXPECT_THROW(CHECK_OPTION_LE(zero, -1), OptionError);
  EXPECT_NO_THROW(CHECK_OPTION_RANGE(zero, 0, 0));
  const std::vector<int> dims = {512, 0};
  try {
    CHECK_OPTION(dims, dims[1] > 0, "be positive");
    FAIL() << "no error";
  } catch (const OptionError& error) {
    EXPECT_EQ(std::string(error.what()), "dims must be positive (got 512,0)");
    EXPECT_EQ(error.Field(), &dims);
    EXPECT_EQ(error.Name(), "dims");
    EXPECT_EQ(error.Value(), "512,0");
  }
}

TEST(OptionManagerCheck, NamesTheFlagBoundToTheFailingField) {
  ToyOptions options;
  OptionManager manager("toy", "");
  manager.AddDefaultOption("Toy.k1", &options.k1);
  manager.AddDefaultOption("Toy.pairing", &options.pairing);
  std::vector<std::string> args = {"toy", "--Toy.k1", "0"};
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  ASSERT_TRUE(manager.Parse(static_cast<int>(argv.size()), argv.data()));
  EXPECT_EQ(manager.FlagName(&options.k1), "--Toy.k1");
  EXPECT_EQ(manager.FlagName(&options.ratio), "");
  try {
    manager.Check([&] { options.Check(); });
    FAIL() << "no error";
  } catch (const OptionError&) {
    FAIL() << "an OptionError about a bound field must become a plain Error";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()),
              "--Toy.k1 must be -1 (the model's value) or >= 1 (got 0)");
  }
  // A field without a flag keeps its own name.
  options.k1 = -1;
  options.ratio = 2;
  try {
    manager.Check([&] { options.Check(); });
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()), "ratio must be in (0, 1] (got 2)");
  }
  options.ratio = 0.5;
  EXPECT_NO_THROW(manager.Check([&] { options.Check(); }));
}

}  // namespace
}  // namespace colmap_gcn
