#pragma once
// LCM channel names of one tongue server. Every channel is UPPER_SNAKE under a configurable
// prefix, so several servers share one bus: prefix "TONGUE_" gives TONGUE_ACTIVATION,
// TONGUE_STATE, TONGUE_MODEL, TONGUE_COMMAND and TONGUE_REJECTION; prefix "TONGUE2_" a second
// server's.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

#include "common/untrusted_text.hpp"

namespace tongue::bus {

inline constexpr std::string_view kDefaultChannelPrefix = "TONGUE_";
// The bus when none is named: multicast on the loopback host only (ttl 0: never leaves it).
// A 4 MB socket receive buffer (capped by the kernel at net.core.rmem_max) holds a whole model
// or state message of a refined tongue: fragments beyond the buffer are dropped unseen.
// The one definition: the Lua, Java and MATLAB step controllers (controllers/lua, java, matlab)
// repeat it, as they cannot include it.
inline constexpr std::string_view kDefaultLcmUrl =
    "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

// The default bus on another udpm port (a run of its own, e.g. the experiment runner's).
inline std::string default_lcm_url_on_port(int port) {
  const std::size_t query = kDefaultLcmUrl.find('?');
  const std::size_t colon = kDefaultLcmUrl.rfind(':', query);
  return std::string(kDefaultLcmUrl.substr(0, colon + 1)) + std::to_string(port) +
         std::string(kDefaultLcmUrl.substr(query));
}

// LCM's longest channel name (LCM_MAX_CHANNEL_NAME_LENGTH in lcm.h): liblcm refuses to publish
// on a longer one, and receivers drop it.
inline constexpr std::size_t kMaxChannelName = 63;
// The longest channel name after the prefix, "ACTIVATION".
inline constexpr std::size_t kLongestChannelSuffix = 10;
inline constexpr std::size_t kMaxChannelPrefix = kMaxChannelName - kLongestChannelSuffix;

// True when every character of prefix is in [A-Z0-9_] (the empty prefix is valid) and the
// channel names it makes fit LCM's limit (at most kMaxChannelPrefix characters).
inline bool is_valid_channel_prefix(std::string_view prefix) {
  if (prefix.size() > kMaxChannelPrefix) return false;
  for (const char c : prefix) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) return false;
  }
  return true;
}

// What is_valid_channel_prefix asks, for messages.
inline constexpr std::string_view kChannelPrefixRule =
    "must contain only A-Z, 0-9 and _ (UPPER_SNAKE), at most 53 characters";
static_assert(kMaxChannelPrefix == 53, "kChannelPrefixRule states the limit");

struct Channels {
  std::string activation;  // lcmt_tongue_activation, controllers -> server
  std::string state;       // lcmt_tongue_state, server -> everyone, once per published step
  std::string model;       // lcmt_tongue_model, server -> everyone, at start and on "describe"
  std::string command;     // lcmt_tongue_command, anyone -> server
  std::string rejection;   // lcmt_tongue_rejection, server -> everyone, per rejected activation

  // Throws std::invalid_argument naming the prefix when is_valid_channel_prefix is false.
  explicit Channels(std::string_view prefix = kDefaultChannelPrefix) {
    if (!is_valid_channel_prefix(prefix)) {
      throw std::invalid_argument("channel prefix " + common::quoted_untrusted(prefix) + " " +
                                  std::string(kChannelPrefixRule));
    }
    const std::string p(prefix);
    activation = p + "ACTIVATION";
    state = p + "STATE";
    model = p + "MODEL";
    command = p + "COMMAND";
    rejection = p + "REJECTION";
  }
};

}  // namespace tongue::bus
