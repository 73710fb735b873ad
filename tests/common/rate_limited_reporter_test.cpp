// At most one line per kind per interval, the next one shown counting those held back; on a
// clock the test moves by hand.
#include "common/rate_limited_reporter.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace tongue::common {
namespace {

class Reporter : public ::testing::Test {
 protected:
  RateLimitedReporter reporter_{1.0, [this](const std::string& line) { lines_.push_back(line); },
                                [this] { return now_; }};
  std::vector<std::string> lines_;
  double now_ = 100.0;  // s
};

TEST_F(Reporter, TheFirstLineOfAKindIsShown) {
  EXPECT_TRUE(reporter_.report("stale", "rejected stale"));
  EXPECT_EQ(lines_, (std::vector<std::string>{"rejected stale"}));
  EXPECT_EQ(reporter_.not_shown("stale"), 0);
}

TEST_F(Reporter, LinesWithinTheIntervalAreCountedNotShown) {
  reporter_.report("stale", "first");
  now_ += 0.5;
  EXPECT_FALSE(reporter_.report("stale", "second"));
  now_ += 0.49;
  EXPECT_FALSE(reporter_.report("stale", "third"));
  EXPECT_EQ(lines_.size(), 1u);
  EXPECT_EQ(reporter_.not_shown("stale"), 2);
}

TEST_F(Reporter, TheNextLineShownSaysHowManyWereNotShown) {
  reporter_.report("stale", "first");
  now_ += 0.1;
  reporter_.report("stale", "second");
  reporter_.report("stale", "third");
  now_ += 0.9;  // one interval after the first line shown
  EXPECT_TRUE(reporter_.report("stale", "fourth"));
  EXPECT_EQ(lines_.back(), "fourth (and 2 more of this kind not shown)");
  EXPECT_EQ(reporter_.not_shown("stale"), 0);
  now_ += 5.0;
  reporter_.report("stale", "fifth");
  EXPECT_EQ(lines_.back(), "fifth");  // nothing held back since
}

TEST_F(Reporter, KindsAreLimitedApart) {
  reporter_.report("stale", "a stale one");
  EXPECT_TRUE(reporter_.report("future", "a future one"));
  EXPECT_FALSE(reporter_.report("stale", "another stale one"));
  EXPECT_EQ(lines_, (std::vector<std::string>{"a stale one", "a future one"}));
  EXPECT_EQ(reporter_.not_shown("future"), 0);
  EXPECT_EQ(reporter_.not_shown("never seen"), 0);
}

TEST_F(Reporter, AFloodGivesOneLinePerInterval) {
  for (int i = 0; i < 10000; ++i) {
    reporter_.report("overrun", "line " + std::to_string(i));
    now_ += 0.001;  // 10 s in all
  }
  EXPECT_GE(lines_.size(), 10u);
  EXPECT_LE(lines_.size(), 11u);
}

TEST(RateLimitedReporter, AZeroIntervalShowsEveryLine) {
  std::vector<std::string> lines;
  RateLimitedReporter reporter(
      0.0, [&lines](const std::string& l) { lines.push_back(l); }, [] { return 1.0; });
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(reporter.report("k", "x"));
  EXPECT_EQ(lines.size(), 3u);
}

TEST(RateLimitedReporter, ANegativeIntervalIsRefused) {
  EXPECT_THROW(RateLimitedReporter(-1.0), std::invalid_argument);
  EXPECT_THROW(RateLimitedReporter(std::numeric_limits<double>::quiet_NaN()),
               std::invalid_argument);
}

}  // namespace
}  // namespace tongue::common
