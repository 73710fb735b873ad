#pragma once
// Shared by the bus fuzz tests: seeded random bytes, every hostile variant of a valid message
// (its truncations, an absurd value in each int32 position, random bytes after its
// fingerprint), and the peak resident memory of a process.
#include <sys/types.h>

#include <cstdint>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace tongue::testing {

using Bytes = std::vector<std::uint8_t>;

inline Bytes random_bytes(std::mt19937& random, std::size_t size) {
  Bytes b(size);
  for (auto& byte : b) byte = static_cast<std::uint8_t>(random());
  return b;
}

// Every proper prefix of whole (the empty one included).
inline std::vector<Bytes> truncations(const Bytes& whole) {
  std::vector<Bytes> out;
  for (std::size_t n = 0; n < whole.size(); ++n) out.emplace_back(whole.begin(), whole.begin() + n);
  return out;
}

// whole with each int32 position from byte 8 on (after the fingerprint) set, in turn, to each
// absurd value: every count and string length of the message gets them.
inline std::vector<Bytes> absurd_int32s(const Bytes& whole) {
  const std::int32_t values[] = {-1, 0, 1 << 24, std::numeric_limits<std::int32_t>::min(),
                                 std::numeric_limits<std::int32_t>::max()};
  std::vector<Bytes> out;
  for (std::size_t at = 8; at + 4 <= whole.size(); ++at) {
    for (const std::int32_t v : values) {
      Bytes b = whole;
      const auto u = static_cast<std::uint32_t>(v);
      for (int i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(u >> (24 - 8 * i));
      out.push_back(std::move(b));
    }
  }
  return out;
}

// The 8-byte fingerprint of whole followed by count messages of random bytes (0-299 bytes).
inline std::vector<Bytes> random_after_fingerprint(const Bytes& whole, std::mt19937& random,
                                                   int count) {
  std::vector<Bytes> out;
  for (int i = 0; i < count; ++i) {
    Bytes b(whole.begin(), whole.begin() + 8);
    const Bytes tail = random_bytes(random, random() % 300);
    b.insert(b.end(), tail.begin(), tail.end());
    out.push_back(std::move(b));
  }
  return out;
}

// A process's peak resident memory [kB] (VmHWM in /proc/PID/status), or -1.
inline long peak_rss_kb(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (in >> key) {
    if (key == "VmHWM:") {
      long kb = -1;
      in >> kb;
      return kb;
    }
    in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return -1;
}

}  // namespace tongue::testing
