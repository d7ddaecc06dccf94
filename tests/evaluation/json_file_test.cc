#include "evaluation/json_file.h"

#include <cmath>

#include <gtest/gtest.h>

#include "evaluation/results.h"
#include "test_utils.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

TEST(JsonFile, WritesSortedIndentedJsonWithFinalNewline) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "record.json");
  Json value = Json::object();
  value["tam"] = size_t{45};
  value["ratio"] = 0.125;
  value["nan"] = std::nan("");
  value["name"] = "a \"quoted\"\nname";
  value["list"] = Json::array();
  value["list"].push_back(1);
  value["list"].push_back("two");
  WriteJsonFile(path, value);
  EXPECT_EQ(ReadTextFile(path),
            "{\n"
            "  \"list\": [\n"
            "    1,\n"
            "    \"two\"\n"
            "  ],\n"
            "  \"name\": \"a \\\"quoted\\\"\\nname\",\n"
            "  \"nan\": null,\n"
            "  \"ratio\": 0.125,\n"
            "  \"tam\": 45\n"
            "}\n");
  const Json parsed = ReadJsonFile(path);
  EXPECT_EQ(parsed.at("tam").get<size_t>(), 45u);
  EXPECT_EQ(parsed.at("name").get<std::string>(), "a \"quoted\"\nname");
  EXPECT_TRUE(parsed.at("nan").is_null());
  EXPECT_EQ(parsed.value("missing", int64_t{7}), 7);
}

TEST(JsonFile, ReplacesBytesThatAreNotUtf8) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "names.json");
  WriteJsonFile(path, Json{{"name", std::string("caf\xe9.jpg")}});
  EXPECT_EQ(ReadJsonFile(path).at("name").get<std::string>(),
            "caf\xef\xbf\xbd.jpg");
}

TEST(JsonFile, InvalidFileNamesTheFile) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "broken.json");
  WriteFileAtomically(path, "{\"a\": }");
  test::ExpectErrorContaining([&] { ReadJsonFile(path); },
                              path + ": invalid JSON: ");
  test::ExpectErrorContaining(
      [&] { ReadJsonFile(JoinPaths(dir.Path(), "missing.json")); },
      "missing.json");
}

// scripts/research/label_real_corpus.sh greps counts as integers from the
// files.
TEST(JsonFile, CountsAreWrittenAsIntegers) {
  MethodResult result;
  result.method = "knn:5";
  result.k = 5;
  result.num_attempted = 45;
  result.num_verified = 30;
  result.retrieval.num_pairs = 45;
  result.retrieval.precision = 1.0;
  const std::string text = MethodResultToJson(result).dump(2);
  EXPECT_NE(text.find("\"tam\": 45,"), std::string::npos) << text;
  EXPECT_NE(text.find("\"um\": 30,"), std::string::npos) << text;
  EXPECT_NE(text.find("\"k\": 5,"), std::string::npos) << text;
  EXPECT_NE(text.find("\"num_pairs\": 45,"), std::string::npos) << text;
  EXPECT_NE(text.find("\"precision\": 1.0,"), std::string::npos) << text;
}

}  // namespace
}  // namespace colmap_gcn
