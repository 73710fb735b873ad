#include "bus/activation_validation.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <utility>

#include "bus/wire_format.hpp"
#include "common/number_text.hpp"
#include "common/untrusted_text.hpp"

namespace tongue::bus {
namespace {

ActivationCheck reject(std::string reason) {
  ActivationCheck check;
  check.reason = std::move(reason);
  return check;
}

}  // namespace

void ActivationCheck::merge_into(Eigen::VectorXd& held) const {
  for (std::size_t i = 0; i < named.size(); ++i) {
    if (named[i] >= static_cast<std::size_t>(held.size()))
      throw std::invalid_argument("ActivationCheck::merge_into: muscle " +
                                  std::to_string(named[i]) + " of " + std::to_string(held.size()));
    held[static_cast<Eigen::Index>(named[i])] = levels[i];
  }
}

ActivationCheck check_activation(const tongue_lcm::lcmt_tongue_activation& msg,
                                 const std::vector<std::string>& muscle_names) {
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
  if (msg.sender.size() > kMaxSenderBytes) {
    return reject("sender is " + std::to_string(msg.sender.size()) + " bytes long, more than " +
                  std::to_string(kMaxSenderBytes));
  }
  for (const char c : msg.sender) {
    // Printable ASCII only: the sender is repeated in logs and notices as it is.
    if (c < 0x20 || c > 0x7e)
      return reject("sender has the byte " + std::to_string(static_cast<unsigned char>(c)) +
                    ", outside printable ASCII");
  }

  // Where each model muscle was first named in the message, or -1.
  std::vector<int> named_at(muscle_names.size(), -1);
  std::vector<std::size_t> muscle_of(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string field =
        "names[" + std::to_string(i) + "] = " + common::quoted_untrusted(msg.names[i]);
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
        "levels[" + std::to_string(i) + "] (" + msg.names[i] + ") = " + common::number_text(level);
    if (!std::isfinite(level)) return reject(value + " is not finite");
    if (level < 0.0 || level > 1.0) return reject(value + " is outside [0, 1]");
  }

  ActivationCheck check;
  check.accepted = true;
  check.named = std::move(muscle_of);
  check.levels = msg.levels;
  return check;
}

bool decode_activation(const void* data, int size, tongue_lcm::lcmt_tongue_activation& out,
                       std::string& reason) {
  // Layout (LCM, big-endian): fingerprint int64, utime int64, step int64, num_muscles int32,
  // num_muscles strings, num_muscles doubles, then the sender string.
  constexpr int kHeader = 8 + 8 + 8 + 4;
  constexpr int kMinStringBytes = 4 + 1;
  constexpr int kDoubleBytes = 8;
  const std::string what = "lcmt_tongue_activation: ";
  WireReader in(data, size);
  if (!in.valid()) {
    reason = what + "no data (size " + std::to_string(size) + ")";
    return false;
  }
  if (size < kHeader) {
    reason = what + "message is " + std::to_string(size) + " bytes, shorter than the " +
             std::to_string(kHeader) + "-byte header";
    return false;
  }
  if (in.int64() != tongue_lcm::lcmt_tongue_activation::getHash()) {
    reason = what + "fingerprint does not match: the bytes are another type or garbage";
    return false;
  }
  in.skip(8 + 8);  // utime and step: check_activation judges the step
  const std::int32_t num_muscles = in.int32();
  const std::string count = "num_muscles = " + std::to_string(num_muscles);
  if (num_muscles < 0) {
    reason = what + count + " is negative";
    return false;
  }
  // Bound the counts by the bytes present before anything is allocated (64-bit arithmetic:
  // num_muscles * 13 can exceed int).
  const std::int64_t needed =
      static_cast<std::int64_t>(num_muscles) * (kMinStringBytes + kDoubleBytes);
  if (needed > in.left()) {
    reason = what + count + " needs at least " + std::to_string(needed) +
             " bytes, the message has " + std::to_string(in.left()) +
             " after the header (truncated?)";
    return false;
  }
  for (std::int32_t i = 0; i < num_muscles; ++i) {
    if (!in.string("names[" + std::to_string(i) + "]", reason)) {
      reason = what + reason;
      return false;
    }
  }
  const std::int64_t level_bytes = static_cast<std::int64_t>(num_muscles) * kDoubleBytes;
  if (in.left() < level_bytes) {
    reason = what + "levels is cut off: " + std::to_string(level_bytes) + " bytes needed, " +
             std::to_string(in.left()) + " left (truncated)";
    return false;
  }
  in.skip(level_bytes);
  if (!in.string("sender", reason)) {
    reason = what + reason;
    return false;
  }
  if (in.left() > 0) {
    reason = what + std::to_string(in.left()) + " trailing bytes after the message";
    return false;
  }
  return checked_decode(data, size, out, what, reason);
}

}  // namespace tongue::bus
