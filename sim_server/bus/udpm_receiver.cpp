#include "bus/udpm_receiver.hpp"

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "bus/channels.hpp"
#include "common/untrusted_text.hpp"

namespace tongue::bus {
namespace {

constexpr std::uint32_t kMagicShort = 0x4c433032;     // "LC02"
constexpr std::uint32_t kMagicFragment = 0x4c433033;  // "LC03"
constexpr std::size_t kShortHeader = 8;
constexpr std::size_t kFragmentHeader = 20;
constexpr std::size_t kLargestDatagram = 65536;  // a UDP payload is at most 65507 bytes

std::uint32_t u32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         std::uint32_t{p[3]};
}
std::uint16_t u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>((p[0] << 8) | p[1]);
}

[[noreturn]] void fail(const LcmUrl& url, const std::string& what) {
  throw std::runtime_error("cannot receive on '" + url.text + "': " + what + ": " +
                           std::strerror(errno));
}

}  // namespace

UdpmReceiver::UdpmReceiver(const LcmUrl& url, std::map<std::string, std::size_t> limits,
                           DropReport on_drop)
    : limits_(std::move(limits)), on_drop_(std::move(on_drop)), datagram_(kLargestDatagram) {
  if (url.provider != LcmUrl::Provider::udpm)
    throw std::invalid_argument("UdpmReceiver: '" + url.text + "' is not a udpm URL");
  fd_ = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd_ < 0) fail(url, "socket");
  try {
    // As liblcm's receive socket: every process on the host binds the same port.
    const int one = 1;
    if (setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0) fail(url, "SO_REUSEADDR");
    if (setsockopt(fd_, SOL_SOCKET, SO_REUSEPORT, &one, sizeof one) != 0) fail(url, "SO_REUSEPORT");
    if (url.recv_buf_size &&
        setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &*url.recv_buf_size, sizeof(int)) != 0)
      fail(url, "SO_RCVBUF");
    // Only the group joined here, not every group some socket of the host joined on the port
    // (Linux's default, ip(7) IP_MULTICAST_ALL).
    const int zero = 0;
    setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_ALL, &zero, sizeof zero);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_ANY);
    address.sin_port = htons(static_cast<std::uint16_t>(url.port));
    if (bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0)
      fail(url, "bind");
    ip_mreq membership{};
    membership.imr_multiaddr.s_addr = htonl(url.group);
    membership.imr_interface.s_addr = htonl(INADDR_ANY);
    if (setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership) != 0)
      fail(url, "joining the multicast group");
  } catch (...) {
    close(fd_);
    throw;
  }
}

UdpmReceiver::~UdpmReceiver() {
  if (fd_ >= 0) close(fd_);
}

void UdpmReceiver::set_limit(const std::string& channel, std::size_t max_bytes) {
  limits_[channel] = max_bytes;
}

bool UdpmReceiver::receive(int timeout_ms, std::size_t max_messages,
                           std::vector<ReceivedMessage>& out) {
  pollfd p{fd_, POLLIN, 0};
  const int ready = poll(&p, 1, timeout_ms < 0 ? 0 : timeout_ms);
  if (ready < 0) {
    if (errno == EINTR) return false;
    throw std::runtime_error(std::string("waiting on the bus socket: ") + std::strerror(errno));
  }
  if (ready == 0) return true;
  const std::size_t goal = out.size() + max_messages;
  while (out.size() < goal && read_datagram(out)) {
  }
  return true;
}

bool UdpmReceiver::read_datagram(std::vector<ReceivedMessage>& out) {
  sockaddr_in from{};
  socklen_t from_size = sizeof from;
  const ssize_t n = recvfrom(fd_, datagram_.data(), datagram_.size(), MSG_DONTWAIT | MSG_TRUNC,
                             reinterpret_cast<sockaddr*>(&from), &from_size);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return false;
    throw std::runtime_error(std::string("reading the bus socket: ") + std::strerror(errno));
  }
  ++clock_;
  const auto size = static_cast<std::size_t>(n);
  if (size > datagram_.size()) {
    drop(drops_.not_lcm, "bad datagram", std::to_string(size) + " bytes, larger than UDP allows");
    return true;
  }
  if (size < kShortHeader) {
    drop(drops_.not_lcm, "bad datagram", std::to_string(size) + " bytes, shorter than a header");
    return true;
  }
  const std::uint32_t magic = u32(datagram_.data());
  const std::uint64_t sender =
      (std::uint64_t{ntohl(from.sin_addr.s_addr)} << 16) | ntohs(from.sin_port);
  if (magic == kMagicShort) {
    on_short(datagram_.data(), size, out);
  } else if (magic == kMagicFragment) {
    on_fragment(datagram_.data(), size, sender, out);
  } else {
    drop(drops_.not_lcm, "bad datagram", "not LCM (magic " + std::to_string(magic) + ")");
  }
  return true;
}

bool UdpmReceiver::channel_at(const std::uint8_t* data, std::size_t size, std::string& channel) {
  const std::size_t longest = std::min(size, kMaxChannelName + 1);
  const auto* end = static_cast<const std::uint8_t*>(std::memchr(data, 0, longest));
  if (end == nullptr) {
    drop(drops_.not_lcm, "bad datagram",
         "no channel name of at most " + std::to_string(kMaxChannelName) + " characters");
    return false;
  }
  channel.assign(reinterpret_cast<const char*>(data), static_cast<std::size_t>(end - data));
  return true;
}

bool UdpmReceiver::limit_of(const std::string& channel, std::size_t& limit) const {
  const auto it = limits_.find(channel);
  if (it == limits_.end()) return false;
  limit = it->second;
  return true;
}

void UdpmReceiver::on_short(const std::uint8_t* data, std::size_t size,
                            std::vector<ReceivedMessage>& out) {
  std::string channel;
  if (!channel_at(data + kShortHeader, size - kShortHeader, channel)) return;
  std::size_t limit = 0;
  if (!limit_of(channel, limit)) return;  // another channel on the bus
  const std::size_t start = kShortHeader + channel.size() + 1;
  const std::size_t payload = size - start;
  if (payload > limit) {
    drop(drops_.oversize, "oversize message",
         std::to_string(payload) + " bytes on " + channel + ", limit " + std::to_string(limit));
    return;
  }
  out.push_back({std::move(channel), std::vector<std::uint8_t>(data + start, data + size)});
}

void UdpmReceiver::on_fragment(const std::uint8_t* data, std::size_t size, std::uint64_t sender,
                               std::vector<ReceivedMessage>& out) {
  if (size < kFragmentHeader) {
    drop(drops_.not_lcm, "bad datagram", "fragment of " + std::to_string(size) + " bytes");
    return;
  }
  const std::uint32_t seqno = u32(data + 4);
  const std::uint32_t declared = u32(data + 8);
  const std::uint32_t offset = u32(data + 12);
  const std::uint16_t number = u16(data + 16);
  const std::uint16_t count = u16(data + 18);
  const std::uint8_t* body = data + kFragmentHeader;
  std::size_t body_size = size - kFragmentHeader;
  Partial* p = partial_of(sender);
  if (number == 0) {
    std::string channel;
    if (!channel_at(body, body_size, channel)) return;
    std::size_t limit = 0;
    if (!limit_of(channel, limit)) return;  // another channel (e.g. the server's own states)
    if (p != nullptr) {
      drop(drops_.incomplete, "incomplete message",
           "a message on " + p->channel + " replaced before its fragment " +
               std::to_string(p->next) + " of " + std::to_string(p->count) + " came");
      forget(p);
    }
    if (declared > limit) {
      drop(drops_.oversize, "oversize message",
           std::to_string(declared) + " bytes declared on " + channel + ", limit " +
               std::to_string(limit));
      return;
    }
    if (offset != 0 || count < 1) {
      drop(drops_.bad_fragment, "bad fragment",
           "first fragment on " + channel + " at offset " + std::to_string(offset) + " of " +
               std::to_string(count) + " fragments");
      return;
    }
    if (partial_.size() >= kMaxPartial) {
      auto oldest = std::min_element(
          partial_.begin(), partial_.end(),
          [](const Partial& a, const Partial& b) { return a.last_used < b.last_used; });
      drop(drops_.incomplete, "incomplete message",
           "a message on " + oldest->channel + " evicted: " + std::to_string(kMaxPartial) +
               " senders' messages already part-way");
      forget(&*oldest);
    }
    body += channel.size() + 1;
    body_size -= channel.size() + 1;
    partial_.push_back({sender, seqno, declared, count, 0, clock_, std::move(channel), {}});
    p = &partial_.back();
  } else if (p == nullptr) {
    return;  // the rest of a message not taken (another channel, or its start was lost)
  } else if (seqno != p->seqno || declared != p->size || count != p->count || number != p->next ||
             offset != p->bytes.size()) {
    drop(drops_.bad_fragment, "bad fragment",
         "fragment " + std::to_string(number) + " of " + std::to_string(count) + " at offset " +
             std::to_string(offset) + " does not continue the message on " + p->channel +
             " (fragment " + std::to_string(p->next) + " of " + std::to_string(p->count) +
             " at offset " + std::to_string(p->bytes.size()) + " expected)");
    forget(p);
    return;
  }
  // 64-bit sums: the declared size and offset are 32-bit values an attacker chooses.
  if (std::uint64_t{p->bytes.size()} + body_size > p->size) {
    drop(drops_.bad_fragment, "bad fragment",
         "fragment " + std::to_string(number) + " runs past the " + std::to_string(p->size) +
             " bytes declared on " + p->channel);
    forget(p);
    return;
  }
  p->bytes.insert(p->bytes.end(), body, body + body_size);
  p->last_used = clock_;
  ++p->next;
  if (p->next < p->count) return;
  if (p->bytes.size() != p->size) {
    drop(drops_.bad_fragment, "bad fragment",
         "message on " + p->channel + " ended at " + std::to_string(p->bytes.size()) + " of " +
             std::to_string(p->size) + " bytes declared");
  } else {
    out.push_back({std::move(p->channel), std::move(p->bytes)});
  }
  forget(p);
}

UdpmReceiver::Partial* UdpmReceiver::partial_of(std::uint64_t sender) {
  for (Partial& p : partial_)
    if (p.sender == sender) return &p;
  return nullptr;
}

void UdpmReceiver::forget(Partial* p) {
  partial_.erase(partial_.begin() + (p - partial_.data()));
}

void UdpmReceiver::drop(std::int64_t& counter, const std::string& kind, const std::string& detail) {
  ++counter;
  if (on_drop_) on_drop_(kind, detail);
}

}  // namespace tongue::bus
