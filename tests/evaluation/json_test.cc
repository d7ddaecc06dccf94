#include "evaluation/json.h"

#include <cmath>

#include <gtest/gtest.h>

#include "util/error.h"

namespace colmap_gcn {
namespace {

TEST(Json, RoundTrip) {
  JsonValue value = JsonValue::Object();
  value["count"] = JsonValue(static_cast<uint64_t>(1234567890123ull));
  value["ratio"] = 0.125;
  value["name"] = "a \"quoted\"\nname";
  value["ok"] = true;
  value["nan"] = std::nan("");
  JsonValue list = JsonValue::Array();
  list.Append(1);
  list.Append("two");
  value["list"] = list;
  for (int indent : {2, -1}) {
    const JsonValue parsed = JsonValue::Parse(value.Dump(indent));
    EXPECT_EQ(parsed.Get("count").AsInt(), 1234567890123ll);
    EXPECT_DOUBLE_EQ(parsed.Get("ratio").AsDouble(), 0.125);
    EXPECT_EQ(parsed.Get("name").AsString(), "a \"quoted\"\nname");
    EXPECT_TRUE(parsed.Get("ok").AsBool());
    EXPECT_TRUE(parsed.Get("nan").IsNull());
    EXPECT_EQ(parsed.Get("list").Size(), 2u);
    EXPECT_EQ(parsed.Get("list").AsArray()[1].AsString(), "two");
    EXPECT_EQ(parsed.Dump(), value.Dump());
  }
  EXPECT_EQ(value.GetIntOr("missing", 7), 7);
  EXPECT_THROW(value.Get("missing"), Error);
  EXPECT_THROW(JsonValue::Parse("{\"a\": }"), Error);
  EXPECT_THROW(JsonValue::Parse("[1, 2"), Error);
}

}  // namespace
}  // namespace colmap_gcn
