#pragma once
// The LCM provider URLs the tongue programs accept, checked before anything opens the bus:
// liblcm 1.3.1 takes an empty URL as "the default bus", only warns about unknown options and
// reads "ttl=abc" as 0. Accepted: udpm://GROUP:PORT[?ttl=N][&recv_buf_size=BYTES] (an IPv4
// multicast group; ttl 0-255, 0 keeping the traffic on the host) and memq:// (in-process).
#include <cstdint>
#include <optional>
#include <string>

namespace tongue::bus {

struct LcmUrl {
  enum class Provider { udpm, memq };
  Provider provider = Provider::udpm;
  std::string text;  // the URL as given, for liblcm and messages
  // udpm only:
  std::uint32_t group = 0;           // IPv4 multicast address, host byte order
  int port = 0;                      // 1-65535
  int ttl = 0;                       // liblcm's default when the URL does not say
  std::optional<int> recv_buf_size;  // bytes asked for the socket receive buffer
};

// Parses url. Throws std::invalid_argument saying what is wrong (empty, unknown provider, bad
// group or port, unknown option, a value that is not a whole number in range).
LcmUrl parse_lcm_url(const std::string& url);

}  // namespace tongue::bus
