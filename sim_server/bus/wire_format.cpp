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

}  // namespace tongue::bus
