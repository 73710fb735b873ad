#include "bus/activation_validation.hpp"

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace tongue::bus {
namespace {

// Shortest text that reads back as the same double ("1.0000001", "nan", "-inf").
std::string number_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (result.ec != std::errc()) return "?";
  return std::string(buffer, result.ptr);
}

std::string quoted(const std::string& text) {
  return "\"" + text + "\"";
}

ActivationCheck reject(std::string reason) {
  ActivationCheck check;
  check.reason = std::move(reason);
  return check;
}

// LCM encodes integers big-endian.
std::uint64_t read_big_endian(const unsigned char* bytes, int count) {
  std::uint64_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8) | bytes[i];
  return value;
}

}  // namespace

ActivationCheck check_activation(const tongue_lcm::lcmt_tongue_activation& msg,
                                 const std::vector<std::string>& muscle_names,
                                 const std::vector<double>& current_levels) {
  if (current_levels.size() != muscle_names.size()) {
    throw std::invalid_argument("check_activation: " + std::to_string(current_levels.size()) +
                                " current levels for " + std::to_string(muscle_names.size()) +
                                " muscles");
  }
  const std::string count = "num_muscles = " + std::to_string(msg.num_muscles);
  if (msg.num_muscles < 0) return reject(count + " is negative");
  const auto n = static_cast<std::size_t>(msg.num_muscles);
  if (msg.names.size() != n) {
    return reject(count + " but names has " + std::to_string(msg.names.size()) + " entries");
  }
  if (msg.levels.size() != n) {
    return reject(count + " but levels has " + std::to_string(msg.levels.size()) + " entries");
  }
  if (msg.step < -1) {
    return reject("step = " + std::to_string(msg.step) + " is not a step (>= 0) or -1 (apply now)");
  }

  // Where each model muscle was first named in the message, or -1.
  std::vector<int> named_at(muscle_names.size(), -1);
  std::vector<std::size_t> muscle_of(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string field = "names[" + std::to_string(i) + "] = " + quoted(msg.names[i]);
    std::size_t m = 0;
    while (m < muscle_names.size() && muscle_names[m] != msg.names[i]) ++m;
    if (m == muscle_names.size()) return reject(field + " is not a muscle of this model");
    if (named_at[m] >= 0) {
      return reject(field + " repeats names[" + std::to_string(named_at[m]) + "]");
    }
    named_at[m] = static_cast<int>(i);
    muscle_of[i] = m;

    const double level = msg.levels[i];
    const std::string value =
        "levels[" + std::to_string(i) + "] (" + msg.names[i] + ") = " + number_text(level);
    if (!std::isfinite(level)) return reject(value + " is not finite");
    if (level < 0.0 || level > 1.0) return reject(value + " is outside [0, 1]");
  }

  ActivationCheck check;
  check.accepted = true;
  check.levels = current_levels;
  for (std::size_t i = 0; i < n; ++i) check.levels[muscle_of[i]] = msg.levels[i];
  check.named = std::move(muscle_of);
  return check;
}

bool decode_activation(const void* data, int size, tongue_lcm::lcmt_tongue_activation& out,
                       std::string& reason) {
  // Layout (LCM, big-endian): fingerprint int64, utime int64, step int64, num_muscles int32,
  // num_muscles strings (int32 length including the terminating NUL, then the bytes), then
  // num_muscles doubles.
  constexpr int kHeader = 8 + 8 + 8 + 4;
  constexpr int kMinStringBytes = 4 + 1;
  constexpr int kDoubleBytes = 8;
  const std::string what = "lcmt_tongue_activation: ";
  if (size < 0 || (data == nullptr && size > 0)) {
    reason = what + "no data (size " + std::to_string(size) + ")";
    return false;
  }
  if (size < kHeader) {
    reason = what + "message is " + std::to_string(size) + " bytes, shorter than the " +
             std::to_string(kHeader) + "-byte header";
    return false;
  }
  const auto* bytes = static_cast<const unsigned char*>(data);
  const auto fingerprint = static_cast<std::int64_t>(read_big_endian(bytes, 8));
  if (fingerprint != tongue_lcm::lcmt_tongue_activation::getHash()) {
    reason = what + "fingerprint does not match: the bytes are another type or garbage";
    return false;
  }
  const auto num_muscles = static_cast<std::int32_t>(read_big_endian(bytes + 24, 4));
  const std::string count = "num_muscles = " + std::to_string(num_muscles);
  if (num_muscles < 0) {
    reason = what + count + " is negative";
    return false;
  }
  // Bound the counts by the bytes present before anything is allocated (64-bit arithmetic:
  // num_muscles * 13 can exceed int).
  const std::int64_t left = size - kHeader;
  const std::int64_t needed =
      static_cast<std::int64_t>(num_muscles) * (kMinStringBytes + kDoubleBytes);
  if (needed > left) {
    reason = what + count + " needs at least " + std::to_string(needed) +
             " bytes, the message has " + std::to_string(left) + " after the header (truncated?)";
    return false;
  }
  std::int64_t pos = kHeader;
  for (std::int32_t i = 0; i < num_muscles; ++i) {
    const std::string field = "names[" + std::to_string(i) + "]";
    if (size - pos < 4) {
      reason = what + field + " is cut off (truncated)";
      return false;
    }
    const auto length = static_cast<std::int32_t>(read_big_endian(bytes + pos, 4));
    pos += 4;
    if (length < 1) {
      reason = what + field + " has string length " + std::to_string(length) +
               " (at least 1, for the terminating NUL)";
      return false;
    }
    if (length > size - pos) {
      reason = what + field + " has string length " + std::to_string(length) + ", only " +
               std::to_string(size - pos) + " bytes left (truncated?)";
      return false;
    }
    if (bytes[pos + length - 1] != 0) {
      reason = what + field + " is not NUL-terminated";
      return false;
    }
    pos += length;
  }
  const std::int64_t level_bytes = static_cast<std::int64_t>(num_muscles) * kDoubleBytes;
  if (size - pos < level_bytes) {
    reason = what + "levels is cut off: " + std::to_string(level_bytes) + " bytes needed, " +
             std::to_string(size - pos) + " left (truncated)";
    return false;
  }
  if (size - pos > level_bytes) {
    reason = what + std::to_string(size - pos - level_bytes) + " trailing bytes after the message";
    return false;
  }
  try {
    if (out.decode(data, 0, size) != size) {
      reason = what + "lcm decode failed";
      return false;
    }
  } catch (const std::exception& e) {
    reason = what + "lcm decode failed: " + e.what();
    return false;
  }
  reason.clear();
  return true;
}

}  // namespace tongue::bus
