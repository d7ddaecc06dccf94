#include "util/logging.h"

#include <regex>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace colmap_gcn {
namespace {

class CapturingSink : public LogSink {
 public:
  void Send(LogLevel level, const std::string& message) override {
    messages.emplace_back(level, message);
  }
  std::vector<std::pair<LogLevel, std::string>> messages;
};

// Restores the minimum level a test changes.
class Logging : public testing::Test {
 protected:
  void TearDown() override { SetMinLogLevel(LogLevel::kInfo); }
};

TEST_F(Logging, WritesOneLineWithGlogPrefixToStderr) {
  testing::internal::CaptureStderr();
  LOG(INFO) << "hello " << 42;
  LOG(WARNING) << "careful";
  LOG(ERROR) << "bad";
  const std::string output = testing::internal::GetCapturedStderr();
  const std::regex expected(
      "I\\d{4} \\d\\d:\\d\\d:\\d\\d logging_test\\.cc:\\d+\\] hello 42\n"
      "W\\d{4} \\d\\d:\\d\\d:\\d\\d logging_test\\.cc:\\d+\\] careful\n"
      "E\\d{4} \\d\\d:\\d\\d:\\d\\d logging_test\\.cc:\\d+\\] bad\n");
  EXPECT_TRUE(std::regex_match(output, expected)) << output;
}

TEST_F(Logging, DropsMessagesBelowTheMinimumLevelWithoutEvaluatingThem) {
  SetMinLogLevel(LogLevel::kWarning);
  EXPECT_FALSE(IsLogLevelEnabled(LogLevel::kInfo));
  EXPECT_TRUE(IsLogLevelEnabled(LogLevel::kError));
  int evaluated = 0;
  const auto count = [&evaluated] { return ++evaluated; };
  CapturingSink sink;
  const ScopedLogSink scoped(&sink);
  testing::internal::CaptureStderr();
  LOG(INFO) << count();
  LOG(WARNING) << count();
  const std::string output = testing::internal::GetCapturedStderr();
  EXPECT_EQ(evaluated, 1);
  ASSERT_EQ(sink.messages.size(), 1u);
  EXPECT_EQ(sink.messages[0].first, LogLevel::kWarning);
  EXPECT_EQ(sink.messages[0].second, "1");
  EXPECT_EQ(output.find("] 1\n"), output.size() - 4) << output;
}

TEST_F(Logging, SinkSeesMessagesOnlyWhileRegistered) {
  CapturingSink sink;
  {
    const ScopedLogSink scoped(&sink);
    LOG(INFO) << "inside";
  }
  LOG(INFO) << "outside";
  ASSERT_EQ(sink.messages.size(), 1u);
  EXPECT_EQ(sink.messages[0].second, "inside");
}

TEST_F(Logging, ProgressLineFormat) {
  EXPECT_EQ(ProgressLogger::FormatLine("embedding", 12, 40),
            "embedding: 12/40 (30 %)");
  EXPECT_EQ(ProgressLogger::FormatLine("none", 0, 0), "none: 0/0 (100 %)");
}

TEST_F(Logging, ProgressLogsEveryTenthAndTheEnd) {
  CapturingSink sink;
  const ScopedLogSink scoped(&sink);
  // An interval no test reaches: only the tenths and the end count.
  ProgressLogger progress(25, "items", 1e9);
  for (int i = 0; i < 25; ++i) progress.Increment();
  EXPECT_EQ(progress.NumDone(), 25u);
  std::vector<std::string> lines;
  for (const auto& [level, message] : sink.messages) lines.push_back(message);
  // 25 items: tenths are reached at 3, 5, 8, 10, 13, 15, 18, 20, 23, 25.
  const std::vector<std::string> expected = {"items: 3/25 (12 %)",
                                             "items: 5/25 (20 %)",
                                             "items: 8/25 (32 %)",
                                             "items: 10/25 (40 %)",
                                             "items: 13/25 (52 %)",
                                             "items: 15/25 (60 %)",
                                             "items: 18/25 (72 %)",
                                             "items: 20/25 (80 %)",
                                             "items: 23/25 (92 %)",
                                             "items: 25/25 (100 %)"};
  EXPECT_EQ(lines, expected);
}

}  // namespace
}  // namespace colmap_gcn
