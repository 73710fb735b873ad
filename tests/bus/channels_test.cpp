#include "bus/channels.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace tongue::bus {
namespace {

TEST(Channels, DefaultPrefixIsTongue) {
  const Channels channels;
  EXPECT_EQ(channels.activation, "TONGUE_ACTIVATION");
  EXPECT_EQ(channels.state, "TONGUE_STATE");
  EXPECT_EQ(channels.model, "TONGUE_MODEL");
  EXPECT_EQ(channels.command, "TONGUE_COMMAND");
}

TEST(Channels, PrefixSeparatesServers) {
  const Channels channels("TONGUE2_");
  EXPECT_EQ(channels.activation, "TONGUE2_ACTIVATION");
  EXPECT_EQ(channels.state, "TONGUE2_STATE");
  EXPECT_EQ(channels.model, "TONGUE2_MODEL");
  EXPECT_EQ(channels.command, "TONGUE2_COMMAND");
}

TEST(Channels, EmptyPrefixIsAllowed) {
  const Channels channels("");
  EXPECT_EQ(channels.state, "STATE");
}

TEST(Channels, BadPrefixThrowsNamingIt) {
  for (const char* prefix : {"tongue_", "TONGUE-", "TONGUE.", "TONGUE ", "TÖNGUE_"}) {
    try {
      const Channels channels(prefix);
      ADD_FAILURE() << "no exception for prefix " << prefix;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(prefix), std::string::npos) << e.what();
    }
  }
}

TEST(Channels, PrefixValidation) {
  EXPECT_TRUE(is_valid_channel_prefix("A_9_Z"));
  EXPECT_TRUE(is_valid_channel_prefix(""));
  EXPECT_FALSE(is_valid_channel_prefix("a"));
  EXPECT_FALSE(is_valid_channel_prefix("A/B"));
}

}  // namespace
}  // namespace tongue::bus
