#pragma once
// Checked decoders of what a tongue server publishes (state, model), for whoever receives them
// (the controllers): the bytes on those channels may come from any process on the bus. Like
// decode_activation and decode_command, each walks the LCM layout with a WireReader (every count
// bounded by the bytes present, every string's length prefix and NUL, no trailing bytes) before
// lcm-gen's decode() runs, so that a forged message is rejected with a reason instead of making
// that decoder throw, allocate without bound or read out of bounds. They also check the relations
// the message definitions state (num_positions = 3 num_nodes, num_rest_positions = 3 num_nodes,
// num_element_nodes = 8 num_elements). out is unspecified on failure.
#include <string>

#include "bus/messages.hpp"

namespace tongue::bus {

bool decode_state(const void* data, int size, tongue_lcm::lcmt_tongue_state& out,
                  std::string& reason);
bool decode_model(const void* data, int size, tongue_lcm::lcmt_tongue_model& out,
                  std::string& reason);

}  // namespace tongue::bus
