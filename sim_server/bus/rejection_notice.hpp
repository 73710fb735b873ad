#pragma once
// Rejection notices (lcmt_tongue_rejection on <prefix>REJECTION): the server tells the sender of
// a rejected activation why, so that a controller whose messages are refused (it names a muscle
// another controller drives, a muscle the model lacks, a level outside [0, 1]) can say so and
// stop instead of waiting for a step that will not come.
#include <cstdint>
#include <string>

#include "bus/messages.hpp"

namespace tongue::bus {

// The notice for rejected, judged when the server's last completed step was step; kind and
// reason as in the server's log. utime: the server's wall clock [microseconds].
tongue_lcm::lcmt_tongue_rejection rejection_notice(
    const tongue_lcm::lcmt_tongue_activation& rejected, std::int64_t step, const std::string& kind,
    const std::string& reason, std::int64_t utime);

// Whether notice is about activation (the same sender, step tag and utime).
bool is_about(const tongue_lcm::lcmt_tongue_rejection& notice,
              const tongue_lcm::lcmt_tongue_activation& activation);

// Decodes raw bytes received on the rejection channel into out. Returns false, with reason
// saying what is wrong, for bytes that are not a whole lcmt_tongue_rejection (too short, another
// type's fingerprint, a bad string, trailing bytes); the structure is checked before lcm-gen's
// decode() runs. out is unspecified on failure.
bool decode_rejection(const void* data, int size, tongue_lcm::lcmt_tongue_rejection& out,
                      std::string& reason);

}  // namespace tongue::bus
