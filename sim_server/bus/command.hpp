#pragma once
// The commands a tongue server takes on <prefix>COMMAND: their one list of names, shared by the
// server, sim_command and the controllers, and the check of the raw bytes of a command message.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "bus/messages.hpp"

namespace tongue::bus {

enum class Command { reset, pause, resume, shutdown, describe };

inline constexpr std::array<Command, 5> kCommands{Command::reset, Command::pause, Command::resume,
                                                  Command::shutdown, Command::describe};

// The name on the bus: "reset", "pause", "resume", "shutdown", "describe".
std::string_view command_name(Command command);

// The command named name exactly, or nullopt.
std::optional<Command> parse_command(std::string_view name);

// Every command's name, in kCommands' order, separated by separator (e.g. "|" for a usage line).
std::string command_names(std::string_view separator);

// The message that sends command, stamped with utime (microseconds).
tongue_lcm::lcmt_tongue_command command_message(Command command, std::int64_t utime);

// Decodes raw bytes received on the command channel (an lcm::ReceiveBuffer's data and
// data_size) into out. Returns false, with reason saying what is wrong, for bytes that are not a
// whole lcmt_tongue_command: too short, another type's fingerprint, a string length below 1
// (the terminating NUL is counted) or beyond the bytes present, a string without its NUL, or
// trailing bytes. The structure is checked before lcm-gen's decode() runs: that one throws or
// reads out of bounds on a hostile length. The name is not checked (parse_command does that).
bool decode_command(const void* data, int size, tongue_lcm::lcmt_tongue_command& out,
                    std::string& reason);

}  // namespace tongue::bus
