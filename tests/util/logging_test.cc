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
  EXPECT_EQ(ProgressLogger::FormatLine("embedding", "images", 12, 40, 4.0),
            "embedding: 12/40 images (30 %), 3.0 images/s, ETA 9.3 s");
  EXPECT_EQ(ProgressLogger::FormatLine("scoring", "", 300, 1000, 2.0),
            "scoring: 300/1000 (30 %), 150/s, ETA 4.7 s");
  // Nothing done yet: no rate, no ETA.
  EXPECT_EQ(ProgressLogger::FormatLine("kNN", "queries", 0, 8, 1.0),
            "kNN: 0/8 queries (0 %)");
  // Unknown total: count and rate only.
  EXPECT_EQ(ProgressLogger::FormatLine("registering", "images", 6, 0, 3.0),
            "registering: 6 images, 2.0 images/s");
  // A described unit rates by its noun.
  EXPECT_EQ(ProgressLogger::FormatLine(
                "adaptive rounds", "images with 3 strong partners", 6, 10, 2.0),
            "adaptive rounds: 6/10 images with 3 strong partners (60 %), 3.0 "
            "images/s, ETA 1.3 s");
  EXPECT_EQ(
      ProgressLogger::FormatFinalLine("embedding", "images", 24, 24, 7.74),
      "embedding: 24/24 images in 7.7 s (3.1 images/s)");
  // Under a tenth of a unit per second: time per unit instead of "0.0/s".
  EXPECT_EQ(ProgressLogger::FormatLine("scene", "methods", 2, 10, 34.0),
            "scene: 2/10 methods (20 %), 17 s/method, ETA 2 min 16 s");
  EXPECT_EQ(ProgressLogger::FormatFinalLine("benchmark", "", 3, 3, 600.0),
            "benchmark: 3/3 in 10 min 00 s (3 min 20 s/item)");
}

TEST_F(Logging, ProgressDurationFormat) {
  EXPECT_EQ(ProgressLogger::FormatDuration(0.42), "0.4 s");
  EXPECT_EQ(ProgressLogger::FormatDuration(12.4), "12 s");
  EXPECT_EQ(ProgressLogger::FormatDuration(185.0), "3 min 05 s");
  EXPECT_EQ(ProgressLogger::FormatDuration(7620.0), "2 h 07 min");
  EXPECT_EQ(ProgressLogger::FormatDuration(-1.0), "0.0 s");
}

// A clock the test advances by hand.
struct FakeClock {
  double now = 100.0;
  ProgressLogger::Clock Function() {
    return [this] { return now; };
  }
};

std::vector<std::string> Messages(const CapturingSink& sink) {
  std::vector<std::string> lines;
  for (const auto& [level, message] : sink.messages) lines.push_back(message);
  return lines;
}

TEST_F(Logging, ProgressLogsEveryTenthAndTheEnd) {
  CapturingSink sink;
  const ScopedLogSink scoped(&sink);
  FakeClock clock;
  ProgressLogger progress(
      25, "items", "", 10.0, ProgressLogger::Mode::kLines, clock.Function());
  clock.now += 2.0;  // past the quiet second; then no time passes
  for (int i = 0; i < 24; ++i) progress.Increment();
  clock.now += 3.0;
  progress.Increment();
  EXPECT_EQ(progress.NumDone(), 25u);
  // 25 items: tenths are reached at 3, 5, 8, 10, 13, 15, 18, 20, 23, 25.
  std::vector<std::string> expected;
  for (const size_t count : {3, 5, 8, 10, 13, 15, 18, 20, 23}) {
    expected.push_back(ProgressLogger::FormatLine("items", "", count, 25, 2.0));
  }
  expected.push_back("items: 25/25 in 5.0 s (5.0/s)");
  EXPECT_EQ(Messages(sink), expected);
  EXPECT_EQ(expected[0], "items: 3/25 (12 %), 1.5/s, ETA 15 s");
  progress.Finish();  // already finished: nothing more
  EXPECT_EQ(sink.messages.size(), expected.size());
}

TEST_F(Logging, ProgressOfAQuickStepLogsNothing) {
  CapturingSink sink;
  const ScopedLogSink scoped(&sink);
  FakeClock clock;
  {
    ProgressLogger progress(10,
                            "kNN",
                            "blocks",
                            10.0,
                            ProgressLogger::Mode::kLines,
                            clock.Function());
    for (int i = 0; i < 10; ++i) {
      clock.now += 0.05;
      progress.Increment();
    }
  }
  EXPECT_TRUE(sink.messages.empty());
}

TEST_F(Logging, ProgressLogsAfterTheIntervalWithinATenth) {
  CapturingSink sink;
  const ScopedLogSink scoped(&sink);
  FakeClock clock;
  ProgressLogger progress(1000,
                          "pairs",
                          "pairs",
                          10.0,
                          ProgressLogger::Mode::kLines,
                          clock.Function());
  progress.Increment(10);  // 1 %, 0 s: too soon (quiet)
  clock.now += 9.0;
  progress.Increment(10);  // 2 %, 9 s: still too soon
  clock.now += 1.0;
  progress.Increment(10);  // 3 %, 10 s since the start: a line
  clock.now += 1.0;
  progress.Increment(10);  // 1 s after that line: none
  ASSERT_EQ(Messages(sink),
            std::vector<std::string>{
                "pairs: 30/1000 pairs (3 %), 3.0 pairs/s, ETA 5 min 23 s"});
}

TEST_F(Logging, ProgressLiveLineIsRedrawnAtMostEveryFewTenthsOfASecond) {
  CapturingSink sink;
  const ScopedLogSink scoped(&sink);
  FakeClock clock;
  std::vector<std::string> drawn;
  {
    ProgressLogger progress(
        4,
        "extracting features",
        "images",
        10.0,
        ProgressLogger::Mode::kLive,
        clock.Function(),
        [&](const std::string& line) { drawn.push_back(line); });
    EXPECT_TRUE(progress.IsLive());
    clock.now += 1.0;
    progress.Update(1);  // first count: drawn
    clock.now += 0.1;
    progress.Update(2);  // 0.1 s later: not redrawn
    clock.now += 0.2;
    progress.Update(3);  // redrawn
    progress.Update(2);  // an older count: ignored
  }                      // destroyed before the end: the final line still comes
  const std::vector<std::string> expected_drawn = {
      "extracting features: 1/4 images (25 %), 1.0 images/s, ETA 3.0 s",
      "extracting features: 3/4 images (75 %), 2.3 images/s, ETA 0.4 s",
      ""};
  EXPECT_EQ(drawn, expected_drawn);
  EXPECT_EQ(Messages(sink),
            std::vector<std::string>{
                "extracting features: 3/4 images in 1.3 s (2.3 images/s)"});
}

TEST_F(Logging, ProgressWithUnknownTotalFinishesWhenDestroyed) {
  CapturingSink sink;
  const ScopedLogSink scoped(&sink);
  FakeClock clock;
  {
    ProgressLogger progress(0,
                            "registering",
                            "images",
                            10.0,
                            ProgressLogger::Mode::kLines,
                            clock.Function());
    clock.now += 2.0;
    progress.Update(4);
  }
  EXPECT_EQ(Messages(sink),
            std::vector<std::string>{"registering: 4 images in 2.0 s "
                                     "(2.0 images/s)"});
}

}  // namespace
}  // namespace colmap_gcn
