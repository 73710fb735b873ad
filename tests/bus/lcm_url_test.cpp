// The LCM URLs accepted up front: what liblcm would take silently (an empty URL, unknown options,
// "ttl=abc") is rejected with a reason.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "bus/channels.hpp"
#include "bus/lcm_url.hpp"

namespace tongue::bus {
namespace {

std::string rejection(const std::string& url) {
  try {
    parse_lcm_url(url);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(LcmUrl, TheDefaultParses) {
  const LcmUrl url = parse_lcm_url(std::string(kDefaultLcmUrl));
  EXPECT_EQ(url.provider, LcmUrl::Provider::udpm);
  EXPECT_EQ(url.group, 0xEFFF4C43u);  // 239.255.76.67
  EXPECT_EQ(url.port, 7667);
  EXPECT_EQ(url.ttl, 0);
  ASSERT_TRUE(url.recv_buf_size.has_value());
  EXPECT_EQ(*url.recv_buf_size, 4194304);
  EXPECT_EQ(parse_lcm_url(default_lcm_url_on_port(7801)).port, 7801);
}

TEST(LcmUrl, MemqAndPlainUdpmParse) {
  EXPECT_EQ(parse_lcm_url("memq://").provider, LcmUrl::Provider::memq);
  const LcmUrl url = parse_lcm_url("udpm://239.255.76.67:7700");
  EXPECT_EQ(url.ttl, 0);
  EXPECT_FALSE(url.recv_buf_size.has_value());
  EXPECT_EQ(parse_lcm_url("udpm://239.255.76.67:7700?ttl=1").ttl, 1);
}

TEST(LcmUrl, BadUrlsAreRejectedWithAReason) {
  const std::pair<std::string, std::string> cases[] = {
      {"", "empty"},
      {"239.255.76.67:7667", "PROVIDER://"},
      {"tcpq://localhost:7700", "unknown provider"},
      {"udpm://239.255.76.67", "GROUP:PORT"},
      {"udpm://239.255.76.67:0", "port"},
      {"udpm://239.255.76.67:70000", "port"},
      {"udpm://239.255.76.67:77x", "port"},
      {"udpm://10.0.0.1:7667", "not a multicast group"},
      {"udpm://not.an.address:7667", "not an IPv4 address"},
      {"udpm://239.255.76.67:7667?ttl=abc", "ttl must be"},
      {"udpm://239.255.76.67:7667?ttl=256", "ttl must be"},
      {"udpm://239.255.76.67:7667?ttl=-1", "ttl must be"},
      {"udpm://239.255.76.67:7667?ttl", "ttl must be"},
      {"udpm://239.255.76.67:7667?recv_buf_size=0", "recv_buf_size"},
      {"udpm://239.255.76.67:7667?recv_buf_size=4MB", "recv_buf_size"},
      {"udpm://239.255.76.67:7667?tll=0", "unknown udpm option 'tll'"},
      {"udpm://239.255.76.67:7667?ttl=0&", "unknown udpm option ''"},
      {"memq://x", "memq:// takes no"},
  };
  for (const auto& [url, expected] : cases)
    EXPECT_NE(rejection(url).find(expected), std::string::npos) << url << ": " << rejection(url);
}

TEST(LcmUrl, AControlCharacterInTheUrlIsEscapedInTheMessage) {
  const std::string message = rejection("udpm://239.255.76.67:7667?x\n=1");
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_NE(message.find("\\n"), std::string::npos) << message;
}

}  // namespace
}  // namespace tongue::bus
