#pragma once
// The receiving side of an LCM udpm bus, in place of liblcm's. liblcm 1.3.1 reassembles
// fragmented messages in a thread of its own with a 32-bit bounds check that a crafted pair of
// fragments overflows (a write out of bounds: SIGSEGV), allocates whatever size a fragment
// claims (up to 256 MB for one 66-byte datagram) and queues every complete message it gets.
// This receiver reads the same socket traffic (LCM's udpm wire format, lcm_udpm.c and
// udpm_util.h of liblcm 1.3.1):
//
//   short message: "LC02" seqno(u32) channel NUL payload
//   fragment:      "LC03" seqno(u32) msg_size(u32) offset(u32) fragment_no(u16) count(u16)
//                  [fragment 0 only: channel NUL] data
//
// (big-endian), in the caller's thread, and keeps only messages on the channels it is given,
// each no larger than its channel's limit: the limit is checked on the size a message or its
// first fragment declares, before anything is copied. A fragmented message is taken in order
// (fragment k at the offset the first k left off, as liblcm sends them) into a buffer that grows
// with the data that actually came, never with the size claimed; at most kMaxPartial senders'
// messages are held part-way. Datagrams are read one at a time and a call returns after at most
// max_messages complete messages, so that the caller handles what comes as it comes.
#include <netinet/in.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "bus/lcm_url.hpp"

namespace tongue::bus {

struct ReceivedMessage {
  std::string channel;
  std::vector<std::uint8_t> bytes;
};

// Why datagrams were dropped, counted since construction.
struct DropCounts {
  std::int64_t not_lcm = 0;       // shorter than a header, unknown magic, bad channel name
  std::int64_t oversize = 0;      // a message declared larger than its channel's limit
  std::int64_t bad_fragment = 0;  // a fragment that does not fit the message it belongs to
  std::int64_t incomplete = 0;    // messages dropped part-way (a fragment lost or evicted)
  std::int64_t total() const { return not_lcm + oversize + bad_fragment + incomplete; }
};

// A drop as it is reported: its kind ("oversize message", ...) and the details.
using DropReport = std::function<void(const std::string& kind, const std::string& detail)>;

class UdpmReceiver {
 public:
  // Senders whose fragmented messages are held part-way at once.
  static constexpr std::size_t kMaxPartial = 4;

  // Opens and joins url's group and port (url.provider must be udpm). limits maps each channel
  // received to its largest message [bytes]; every other channel is ignored. on_drop, when
  // given, hears of every drop. Throws std::runtime_error when the socket cannot be set up.
  UdpmReceiver(const LcmUrl& url, std::map<std::string, std::size_t> limits,
               DropReport on_drop = {});
  ~UdpmReceiver();
  UdpmReceiver(const UdpmReceiver&) = delete;
  UdpmReceiver& operator=(const UdpmReceiver&) = delete;

  void set_limit(const std::string& channel, std::size_t max_bytes);

  // Waits at most timeout_ms (0: not at all) for a datagram, then reads the waiting ones until
  // max_messages messages are complete or none is left, appending the messages to out in order.
  // Returns false when the wait was cut short by a signal. Throws std::runtime_error when the
  // socket fails.
  bool receive(int timeout_ms, std::size_t max_messages, std::vector<ReceivedMessage>& out);

  const DropCounts& drops() const { return drops_; }

 private:
  struct Partial {
    std::uint64_t sender = 0;
    std::uint32_t seqno = 0;
    std::uint32_t size = 0;  // declared, checked against the channel's limit
    std::uint16_t count = 0;
    std::uint16_t next = 0;  // the fragment expected next
    std::uint64_t last_used = 0;
    std::string channel;
    std::vector<std::uint8_t> bytes;
  };

  // Reads one datagram; false when none is waiting.
  bool read_datagram(std::vector<ReceivedMessage>& out);
  void on_short(const std::uint8_t* data, std::size_t size, std::vector<ReceivedMessage>& out);
  void on_fragment(const std::uint8_t* data, std::size_t size, std::uint64_t sender,
                   std::vector<ReceivedMessage>& out);
  // The channel name at data (NUL within size, LCM's length limit), or false.
  bool channel_at(const std::uint8_t* data, std::size_t size, std::string& channel);
  // The channel's limit; false when it is not received.
  bool limit_of(const std::string& channel, std::size_t& limit) const;
  void drop(std::int64_t& counter, const std::string& kind, const std::string& detail);
  Partial* partial_of(std::uint64_t sender);
  void forget(Partial* p);

  int fd_ = -1;
  std::map<std::string, std::size_t> limits_;
  DropReport on_drop_;
  DropCounts drops_;
  std::vector<Partial> partial_;
  std::uint64_t clock_ = 0;  // datagrams read, the age of a partial message
  std::vector<std::uint8_t> datagram_;
};

}  // namespace tongue::bus
