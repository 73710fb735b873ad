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
  // Layout (lcmtypes/lcmt_tongue_rejection.lcm, LCM big-endian): fingerprint int64, utime int64,
  // step int64, sender string, activation_step int64, activation_utime int64, kind string,
  // reason string.
  constexpr int kMinString = 4 + 1;  // the shortest string: its length and the NUL
  constexpr int kShortest = 8 + 8 + 8 + kMinString + 8 + 8 + 2 * kMinString;
  const std::string what = "lcmt_tongue_rejection: ";
  WireReader in(data, size);
  if (!start_message(in, tongue_lcm::lcmt_tongue_rejection::getHash(), kShortest, what, reason))
    return false;
  const bool laid_out = in.fixed("utime, step", 8 + 8, reason) && in.string("sender", reason) &&
                        in.fixed("activation_step, activation_utime", 8 + 8, reason) &&
                        in.string("kind", reason) && in.string("reason", reason) &&
                        in.at_end(reason);
  if (!laid_out) {
    reason = what + reason;
    return false;
  }
  return checked_decode(data, size, out, what, reason);
}

}  // namespace tongue::bus
