// Received text as reports print it: one line, bounded, every byte visible.
#include <gtest/gtest.h>

#include <string>

#include "common/untrusted_text.hpp"

namespace tongue::common {
namespace {

TEST(UntrustedText, PrintableTextIsKept) {
  EXPECT_EQ(untrusted_text("GGp_left"), "GGp_left");
  EXPECT_EQ(quoted_untrusted("shutdown"), "\"shutdown\"");
}

// A name that would forge a report line of its own.
TEST(UntrustedText, NewlinesAndControlBytesAreEscaped) {
  const std::string forged = "x\nsim_server: shutdown at step 99";
  const std::string shown = untrusted_text(forged, 100);
  EXPECT_EQ(shown.find('\n'), std::string::npos);
  EXPECT_EQ(shown, "x\\nsim_server: shutdown at step 99");
  EXPECT_EQ(untrusted_text(std::string("a\0b\x1b[2J\t\r\\\x7f\xff", 12)),
            "a\\x00b\\x1b[2J\\t\\r\\\\\\x7f\\xff");
}

TEST(UntrustedText, LongTextIsCutAndItsSizeSaid) {
  const std::string megabyte(1 << 20, 'a');
  const std::string shown = untrusted_text(megabyte);
  EXPECT_EQ(shown, std::string(kUntrustedTextShown, 'a') + "...(1048576 bytes)");
  EXPECT_EQ(untrusted_text("abcdef", 3), "abc...(6 bytes)");
}

}  // namespace
}  // namespace tongue::common
