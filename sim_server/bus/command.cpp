#include "bus/command.hpp"

#include "bus/wire_format.hpp"

namespace tongue::bus {

std::string_view command_name(Command command) {
  switch (command) {
    case Command::reset:
      return "reset";
    case Command::pause:
      return "pause";
    case Command::resume:
      return "resume";
    case Command::shutdown:
      return "shutdown";
    case Command::describe:
      return "describe";
  }
  return "?";
}

std::optional<Command> parse_command(std::string_view name) {
  for (const Command c : kCommands)
    if (command_name(c) == name) return c;
  return std::nullopt;
}

std::string command_names(std::string_view separator) {
  std::string text;
  for (const Command c : kCommands) {
    if (!text.empty()) text += separator;
    text += command_name(c);
  }
  return text;
}

tongue_lcm::lcmt_tongue_command command_message(Command command, std::int64_t utime) {
  tongue_lcm::lcmt_tongue_command msg;
  msg.utime = utime;
  msg.command = std::string(command_name(command));
  return msg;
}

bool decode_command(const void* data, int size, tongue_lcm::lcmt_tongue_command& out,
                    std::string& reason) {
  // Layout (LCM, big-endian): fingerprint int64, utime int64, then the string: int32 length
  // including the terminating NUL, then the bytes.
  constexpr int kHeader = 8 + 8;
  const std::string what = "lcmt_tongue_command: ";
  WireReader in(data, size);
  if (!in.valid()) {
    reason = what + "no data (size " + std::to_string(size) + ")";
    return false;
  }
  if (size < kHeader + 4 + 1) {
    reason = what + "message is " + std::to_string(size) + " bytes, shorter than the " +
             std::to_string(kHeader + 4 + 1) + " of the shortest command";
    return false;
  }
  if (in.int64() != tongue_lcm::lcmt_tongue_command::getHash()) {
    reason = what + "fingerprint does not match: the bytes are another type or garbage";
    return false;
  }
  in.skip(8);  // utime: any value is a time
  if (!in.string("command", reason)) {
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
