#include "bus/lcm_url.hpp"

#include <arpa/inet.h>

#include <charconv>
#include <stdexcept>
#include <string_view>

#include "common/untrusted_text.hpp"

namespace tongue::bus {
namespace {

[[noreturn]] void bad(const std::string& url, const std::string& why) {
  throw std::invalid_argument("LCM URL '" + common::untrusted_text(url) + "': " + why);
}

// value as a whole number in [lo, hi], or nullopt.
std::optional<long> whole_number(std::string_view value, long lo, long hi) {
  long n = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
  if (value.empty() || ec != std::errc() || end != value.data() + value.size() || n < lo || n > hi)
    return std::nullopt;
  return n;
}

void read_udpm_network(const std::string& url, std::string_view network, LcmUrl& out) {
  const std::size_t colon = network.find(':');
  if (colon == std::string_view::npos) bad(url, "udpm needs GROUP:PORT, e.g. 239.255.76.67:7667");
  const std::string address(network.substr(0, colon));
  in_addr group{};
  if (inet_pton(AF_INET, address.c_str(), &group) != 1)
    bad(url, "'" + common::untrusted_text(address) + "' is not an IPv4 address");
  out.group = ntohl(group.s_addr);
  if ((out.group >> 28) != 0xE) bad(url, address + " is not a multicast group (224.0.0.0/4)");
  const auto port = whole_number(network.substr(colon + 1), 1, 65535);
  if (!port) bad(url, "the port must be a whole number in 1-65535");
  out.port = static_cast<int>(*port);
}

void read_udpm_option(const std::string& url, std::string_view option, LcmUrl& out) {
  const std::size_t eq = option.find('=');
  const std::string_view key = option.substr(0, eq);
  const std::string_view value = eq == std::string_view::npos ? "" : option.substr(eq + 1);
  if (key == "ttl") {
    const auto ttl = whole_number(value, 0, 255);
    if (!ttl) bad(url, "ttl must be a whole number in 0-255");
    out.ttl = static_cast<int>(*ttl);
  } else if (key == "recv_buf_size") {
    const auto size = whole_number(value, 1, 2147483647);
    if (!size) bad(url, "recv_buf_size must be a whole number of bytes in 1-2147483647");
    out.recv_buf_size = static_cast<int>(*size);
  } else {
    bad(url,
        "unknown udpm option '" + common::untrusted_text(key) + "' (known: ttl, recv_buf_size)");
  }
}

}  // namespace

LcmUrl parse_lcm_url(const std::string& url) {
  if (url.empty()) bad(url, "empty (name the bus, e.g. udpm://239.255.76.67:7667?ttl=0)");
  LcmUrl out;
  out.text = url;
  const std::size_t scheme_end = url.find("://");
  if (scheme_end == std::string::npos) bad(url, "expected PROVIDER://...");
  const std::string_view provider = std::string_view(url).substr(0, scheme_end);
  const std::string_view rest = std::string_view(url).substr(scheme_end + 3);
  const std::size_t query = rest.find('?');
  const std::string_view network = rest.substr(0, query);
  const std::string_view options =
      query == std::string_view::npos ? std::string_view() : rest.substr(query + 1);
  if (provider == "memq") {
    if (!rest.empty()) bad(url, "memq:// takes no address or options");
    out.provider = LcmUrl::Provider::memq;
    return out;
  }
  if (provider != "udpm") bad(url, "unknown provider (known: udpm, memq)");
  read_udpm_network(url, network, out);
  if (query == std::string_view::npos) return out;
  std::size_t start = 0;
  while (start <= options.size()) {
    const std::size_t amp = options.find('&', start);
    const std::string_view option =
        options.substr(start, amp == std::string_view::npos ? std::string_view::npos : amp - start);
    read_udpm_option(url, option, out);
    if (amp == std::string_view::npos) break;
    start = amp + 1;
  }
  return out;
}

}  // namespace tongue::bus
