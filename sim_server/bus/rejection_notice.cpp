#include "bus/rejection_notice.hpp"

#include "bus/wire_format.hpp"

namespace tongue::bus {

tongue_lcm::lcmt_tongue_rejection rejection_notice(
    const tongue_lcm::lcmt_tongue_activation& rejected, std::int64_t step, const std::string& kind,
    const std::string& reason, std::int64_t utime) {
  tongue_lcm::lcmt_tongue_rejection notice;
  notice.utime = utime;
  notice.step = step;
  notice.sender = rejected.sender;
  notice.activation_step = rejected.step;
  notice.activation_utime = rejected.utime;
  notice.kind = kind;
  notice.reason = reason;
  return notice;
}

bool is_about(const tongue_lcm::lcmt_tongue_rejection& notice,
              const tongue_lcm::lcmt_tongue_activation& activation) {
  return notice.sender == activation.sender && notice.activation_step == activation.step &&
         notice.activation_utime == activation.utime;
}

bool decode_rejection(const void* data, int size, tongue_lcm::lcmt_tongue_rejection& out,
                      std::string& reason) {
  // Layout (LCM, big-endian): fingerprint int64, utime int64, step int64, sender string,
  // activation_step int64, activation_utime int64, kind string, reason string.
  constexpr int kStringBytes = 4 + 1;  // the shortest string: its length and the NUL
  constexpr int kShortest = 8 + 8 + 8 + kStringBytes + 8 + 8 + 2 * kStringBytes;
  const std::string what = "lcmt_tongue_rejection: ";
  WireReader in(data, size);
  if (!in.valid()) {
    reason = what + "no data (size " + std::to_string(size) + ")";
    return false;
  }
  if (size < kShortest) {
    reason = what + "message is " + std::to_string(size) + " bytes, shorter than the " +
             std::to_string(kShortest) + " of the shortest notice";
    return false;
  }
  if (in.int64() != tongue_lcm::lcmt_tongue_rejection::getHash()) {
    reason = what + "fingerprint does not match: the bytes are another type or garbage";
    return false;
  }
  in.skip(8 + 8);  // utime and step
  bool ok = in.string("sender", reason);
  if (ok && in.left() < 8 + 8) {
    reason = "activation_step is cut off (truncated)";
    ok = false;
  }
  if (ok) in.skip(8 + 8);  // activation_step and activation_utime
  ok = ok && in.string("kind", reason) && in.string("reason", reason);
  if (!ok) {
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
