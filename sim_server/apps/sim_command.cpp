// sim_command COMMAND [--lcm-url URL] [--prefix TONGUE_]
//
// Sends one command (reset, pause, resume, shutdown, describe) to a running sim_server on
// <prefix>COMMAND, so that a user or a script can steer a server from a shell. It does not wait
// for an answer: the server reports what it did on its own stderr and in its next state.
//
// Exit status (common/exit_code.hpp): 0 sent; 1 bad command line or the bus could not be opened
// or written.
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

#include <lcm/lcm-cpp.hpp>

#include "bus/channels.hpp"
#include "bus/command.hpp"
#include "bus/lcm_url.hpp"
#include "bus/messages.hpp"
#include "common/exit_code.hpp"
#include "common/untrusted_text.hpp"

namespace {

void print_usage(std::FILE* to) {
  std::fprintf(to,
               "usage: sim_command %s [--lcm-url URL]\n"
               "                   [--prefix TONGUE_]\n"
               "  --lcm-url  LCM provider URL (default %s)\n"
               "  --prefix   channel prefix of the server, A-Z 0-9 _ (default TONGUE_)\n",
               tongue::bus::command_names("|").c_str(),
               std::string(tongue::bus::kDefaultLcmUrl).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  using tongue::common::kExitError;
  using tongue::common::kExitOk;
  std::optional<tongue::bus::Command> command;
  std::string url(tongue::bus::kDefaultLcmUrl);
  std::string prefix(tongue::bus::kDefaultChannelPrefix);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      print_usage(stdout);
      return kExitOk;
    }
    if (arg == "--lcm-url" || arg == "--prefix") {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "sim_command: %s needs a value\n", arg.c_str());
        return kExitError;
      }
      (arg == "--lcm-url" ? url : prefix) = argv[++i];
    } else if (command || !tongue::bus::parse_command(arg)) {
      std::fprintf(stderr, "sim_command: unexpected argument %s\n",
                   tongue::common::quoted_untrusted(arg).c_str());
      print_usage(stderr);
      return kExitError;
    } else {
      command = tongue::bus::parse_command(arg);
    }
  }
  if (!command) {
    print_usage(stderr);
    return kExitError;
  }
  try {
    tongue::bus::parse_lcm_url(url);
    const tongue::bus::Channels channels(prefix);
    lcm::LCM lcm(url);
    if (!lcm.good()) {
      std::fprintf(stderr, "sim_command: cannot open the LCM bus '%s'\n", url.c_str());
      return kExitError;
    }
    const tongue_lcm::lcmt_tongue_command message = tongue::bus::command_message(
        *command, std::chrono::duration_cast<std::chrono::microseconds>(
                      std::chrono::system_clock::now().time_since_epoch())
                      .count());
    if (lcm.publish(channels.command, &message) != 0) {
      std::fprintf(stderr, "sim_command: could not publish on %s\n", channels.command.c_str());
      return kExitError;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sim_command: %s\n", e.what());
    return kExitError;
  }
  return kExitOk;
}
