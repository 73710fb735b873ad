#pragma once
// The main() of every controller program: parse the command line (common options plus the
// program's own), build the controller from its input files, run the control loop, print the
// summary line, and map errors to exit statuses (control_loop.hpp): 1 for a bad command line,
// a bad input file (the message names the file and the key) or a bus error.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "controller/command_line.hpp"
#include "controller/controller.hpp"

namespace tongue::controller {

struct ProgramSpec {
  std::string name;                           // e.g. "ep_controller"
  std::string synopsis;                       // e.g. "--plan FILE [--delay-ms D]"
  std::string options_usage;                  // the program's option lines for --help
  std::vector<std::string> options;           // its options, e.g. {"--plan", "--delay-ms"}
  std::vector<std::string> required_options;  // those that must be given
  // Builds the controller; may throw UsageError (a bad option value) or InputError (a bad file).
  std::function<std::unique_ptr<Controller>(const CommandLine&)> make_controller;
};

int controller_main(int argc, const char* const* argv, const ProgramSpec& spec);

}  // namespace tongue::controller
