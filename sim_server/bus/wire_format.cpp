#include "bus/wire_format.hpp"

#include <stdexcept>

namespace tongue::bus {

WireReader::WireReader(const void* data, int size)
    : bytes_(static_cast<const unsigned char*>(data)),
      size_(size),
      valid_(size >= 0 && (data != nullptr || size == 0)) {}

std::uint64_t WireReader::big_endian(int count) {
  if (left() < count)
    throw std::logic_error("WireReader: " + std::to_string(count) + " bytes asked for, " +
                           std::to_string(left()) + " left");
  std::uint64_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8) | bytes_[pos_ + i];
  pos_ += count;
  return value;
}

std::int64_t WireReader::int64() {
  return static_cast<std::int64_t>(big_endian(8));
}

std::int32_t WireReader::int32() {
  return static_cast<std::int32_t>(big_endian(4));
}

void WireReader::skip(std::int64_t count) {
  if (count < 0 || left() < count)
    throw std::logic_error("WireReader: cannot skip " + std::to_string(count) + " bytes, " +
                           std::to_string(left()) + " left");
  pos_ += count;
}

bool WireReader::string(const std::string& field, std::string& reason) {
  if (left() < 4) {
    reason = field + " is cut off (truncated)";
    return false;
  }
  const std::int32_t length = int32();
  if (length < 1) {
    reason = field + " has string length " + std::to_string(length) +
             " (at least 1, for the terminating NUL)";
    return false;
  }
  if (length > left()) {
    reason = field + " has string length " + std::to_string(length) + ", only " +
             std::to_string(left()) + " bytes left (truncated?)";
    return false;
  }
  if (bytes_[pos_ + length - 1] != 0) {
    reason = field + " is not NUL-terminated";
    return false;
  }
  pos_ += length;
  return true;
}

bool WireReader::fixed(const std::string& field, std::int64_t bytes, std::string& reason) {
  if (left() < bytes) {
    reason = field + " is cut off: " + std::to_string(bytes) + " bytes needed, " +
             std::to_string(left()) + " left (truncated)";
    return false;
  }
  pos_ += bytes;
  return true;
}

bool WireReader::count(const std::string& field, std::int64_t min_bytes_each, std::int32_t& n,
                       std::string& reason) {
  if (left() < 4) {
    reason = field + " is cut off (truncated)";
    return false;
  }
  n = int32();
  if (n < 0) {
    reason = field + " = " + std::to_string(n) + " is negative";
    return false;
  }
  // 64-bit: n * min_bytes_each can exceed int32.
  const std::int64_t needed = static_cast<std::int64_t>(n) * min_bytes_each;
  if (needed > left()) {
    reason = field + " = " + std::to_string(n) + " needs at least " + std::to_string(needed) +
             " bytes, " + std::to_string(left()) + " left (truncated?)";
    return false;
  }
  return true;
}

bool WireReader::strings(const std::string& field, std::int32_t count, std::string& reason) {
  for (std::int32_t i = 0; i < count; ++i)
    if (!string(field + "[" + std::to_string(i) + "]", reason)) return false;
  return true;
}

bool WireReader::at_end(std::string& reason) const {
  if (left() == 0) return true;
  reason = std::to_string(left()) + " trailing bytes after the message";
  return false;
}

bool start_message(WireReader& in, std::int64_t fingerprint, std::int64_t min_size,
                   const std::string& what, std::string& reason) {
  if (!in.valid()) {
    reason = what + "no data";
    return false;
  }
  if (in.left() < min_size) {
    reason = what + "message is " + std::to_string(in.left()) + " bytes, shorter than the " +
             std::to_string(min_size) + " of the shortest one";
    return false;
  }
  if (in.int64() != fingerprint) {
    reason = what + "fingerprint does not match: the bytes are another type or garbage";
    return false;
  }
  return true;
}

}  // namespace tongue::bus
