#pragma once
// Bytes of LCM messages for the decoder tests: a message encoded as a server would receive it,
// and an int32 overwritten in place to make it hostile.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tongue::bus::testing {

template <typename Message>
std::vector<std::uint8_t> encoded(const Message& msg) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// Overwrites the big-endian int32 at offset (LCM's byte order).
inline void put_int32(std::vector<std::uint8_t>& bytes, std::size_t offset, std::int32_t value) {
  const auto v = static_cast<std::uint32_t>(value);
  for (int i = 0; i < 4; ++i) bytes[offset + i] = static_cast<std::uint8_t>(v >> (24 - 8 * i));
}

}  // namespace tongue::bus::testing
