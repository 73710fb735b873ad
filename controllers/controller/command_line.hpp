#pragma once
// The command line every controller shares (--lcm-url, --prefix, --mode, --max-steps,
// --timeout-s), parsed together with the program's own options. An experiment runner starts the
// controllers against exactly this contract; see control_loop.hpp for what each option does.
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bus/channels.hpp"

namespace tongue::controller {

// lockstep: answer the state of step k with the activation for step k + 1, the server advancing
// when it arrives. realtime: answer each state with an activation for step -1 ("apply now"),
// which the real-time server holds until the next one.
enum class LoopMode { lockstep, realtime };

struct CommonOptions {
  std::string lcm_url{bus::kDefaultLcmUrl};
  std::string prefix{bus::kDefaultChannelPrefix};
  LoopMode mode = LoopMode::lockstep;
  std::optional<std::int64_t> max_steps;  // send nothing for later steps, exit 0 after this one
  double timeout_s = 5.0;                 // s without the model or a state before giving up
};

// A bad command line; what() says what is wrong (the program prints it and its usage, exit 1).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CommandLine {
  CommonOptions common;
  std::map<std::string, std::string> values;  // the program's own options that were given
  bool help = false;                          // --help or -h
};

// Parses "--name value" and "--name=value". program_options are the program's own options
// (e.g. "--plan"), each taking one value. Throws UsageError for an unknown option, a missing
// value, a positional argument or a bad common value (mode, prefix outside A-Z 0-9 _, max-steps
// not an integer >= 0, timeout not a number in (0, 3600] s).
CommandLine parse_command_line(int argc, const char* const* argv,
                               const std::vector<std::string>& program_options);

// The usage lines of the common options, for each program's --help.
std::string common_usage();

// Number parsing for the programs' own options (the rule of common/number_text.hpp); UsageError
// naming the option when text is not one finite number.
double parse_number(const std::string& option, const std::string& text);

}  // namespace tongue::controller
