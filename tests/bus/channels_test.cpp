#include "bus/channels.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#ifndef TONGUE_SOURCE_DIR
#error "TONGUE_SOURCE_DIR must name the source tree"
#endif

namespace tongue::bus {
namespace {

TEST(Channels, DefaultPrefixIsTongue) {
  const Channels channels;
  EXPECT_EQ(channels.activation, "TONGUE_ACTIVATION");
  EXPECT_EQ(channels.state, "TONGUE_STATE");
  EXPECT_EQ(channels.model, "TONGUE_MODEL");
  EXPECT_EQ(channels.command, "TONGUE_COMMAND");
  EXPECT_EQ(channels.rejection, "TONGUE_REJECTION");
}

TEST(Channels, PrefixSeparatesServers) {
  const Channels channels("TONGUE2_");
  EXPECT_EQ(channels.activation, "TONGUE2_ACTIVATION");
  EXPECT_EQ(channels.state, "TONGUE2_STATE");
  EXPECT_EQ(channels.model, "TONGUE2_MODEL");
  EXPECT_EQ(channels.command, "TONGUE2_COMMAND");
  EXPECT_EQ(channels.rejection, "TONGUE2_REJECTION");
}

TEST(Channels, EmptyPrefixIsAllowed) {
  const Channels channels("");
  EXPECT_EQ(channels.state, "STATE");
}

TEST(Channels, BadPrefixThrowsNamingIt) {
  // Named as printed: bytes outside printable ASCII escaped.
  const std::pair<std::string, std::string> cases[] = {
      {"tongue_", "tongue_"}, {"TONGUE-", "TONGUE-"},          {"TONGUE.", "TONGUE."},
      {"TONGUE ", "TONGUE "}, {"TÖNGUE_", "T\\xc3\\x96NGUE_"}, {"A\nB", "A\\nB"}};
  for (const auto& [prefix, shown] : cases) {
    try {
      const Channels channels(prefix);
      ADD_FAILURE() << "no exception for prefix " << prefix;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("\"" + shown + "\""), std::string::npos) << e.what();
    }
  }
}

// LCM's channel names are at most 63 characters: the prefix leaves room for "ACTIVATION".
TEST(Channels, PrefixLengthFitsLcmChannelNames) {
  const std::string longest(kMaxChannelPrefix, 'A');
  EXPECT_TRUE(is_valid_channel_prefix(longest));
  EXPECT_EQ(Channels(longest).activation.size(), kMaxChannelName);
  EXPECT_FALSE(is_valid_channel_prefix(longest + "A"));
  EXPECT_THROW(Channels(std::string(300, 'A')), std::invalid_argument);
}

TEST(Channels, PrefixValidation) {
  EXPECT_TRUE(is_valid_channel_prefix("A_9_Z"));
  EXPECT_TRUE(is_valid_channel_prefix(""));
  EXPECT_FALSE(is_valid_channel_prefix("a"));
  EXPECT_FALSE(is_valid_channel_prefix("A/B"));
}

TEST(Channels, DefaultUrlOnAnotherPortKeepsItsOptions) {
  EXPECT_EQ(default_lcm_url_on_port(7801), "udpm://239.255.76.67:7801?ttl=0&recv_buf_size=4194304");
}

// The Lua controller cannot include channels.hpp and repeats the default URL: the two agree.
TEST(Channels, LuaControllerHasTheSameDefaultUrl) {
  std::ifstream in(std::string(TONGUE_SOURCE_DIR) + "/controllers/lua/step_controller.lua");
  ASSERT_TRUE(in);
  std::stringstream text;
  text << in.rdbuf();
  const std::string line = "local DEFAULT_URL = \"" + std::string(kDefaultLcmUrl) + "\"";
  EXPECT_NE(text.str().find(line), std::string::npos) << "not in step_controller.lua: " << line;
}

}  // namespace
}  // namespace tongue::bus
