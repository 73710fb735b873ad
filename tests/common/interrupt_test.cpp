#include "common/interrupt.hpp"

#include <gtest/gtest.h>

#include <csignal>

namespace tongue::common {
namespace {

TEST(InterruptHandlers, SignalSetsTheFlagInsteadOfEndingTheProcess) {
  struct sigaction before {};
  sigaction(SIGINT, nullptr, &before);
  {
    const InterruptHandlers interrupt;
    EXPECT_FALSE(interrupt.raised());
    std::raise(SIGTERM);
    EXPECT_TRUE(interrupt.raised());
    EXPECT_EQ(interrupt.signal_number(), SIGTERM);
    EXPECT_STREQ(interrupt.signal_name(), "SIGTERM");
  }
  // A new object starts clear; the previous handler came back in between.
  struct sigaction now {};
  sigaction(SIGINT, nullptr, &now);
  EXPECT_EQ(now.sa_handler, before.sa_handler);
  const InterruptHandlers again;
  EXPECT_FALSE(again.raised());
  std::raise(SIGINT);
  EXPECT_STREQ(again.signal_name(), "SIGINT");
}

}  // namespace
}  // namespace tongue::common
