#include "controller/controller_main.hpp"

#include <cstdio>
#include <exception>

#include "controller/control_loop.hpp"

namespace tongue::controller {
namespace {

void print_usage(std::FILE* to, const ProgramSpec& spec) {
  std::fprintf(to, "usage: %s %s [common options]\n%s%s", spec.name.c_str(), spec.synopsis.c_str(),
               spec.options_usage.c_str(), common_usage().c_str());
}

}  // namespace

int controller_main(int argc, const char* const* argv, const ProgramSpec& spec) {
  CommandLine command_line;
  std::unique_ptr<Controller> controller;
  try {
    command_line = parse_command_line(argc, argv, spec.options);
    if (command_line.help) {
      print_usage(stdout, spec);
      return kExitOk;
    }
    for (const std::string& option : spec.required_options)
      if (!command_line.values.count(option)) throw UsageError(option + " is required");
    controller = spec.make_controller(command_line);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s\n", spec.name.c_str(), e.what());
    print_usage(stderr, spec);
    return kExitError;
  } catch (const std::exception& e) {  // InputError: names the file and the key
    std::fprintf(stderr, "%s: error: %s\n", spec.name.c_str(), e.what());
    return kExitError;
  }
  const LoopOutcome outcome = run_control_loop(spec.name, command_line.common, *controller);
  std::fprintf(
      stderr, "%s\n",
      summary_line(spec.name, outcome, command_line.common, controller->summary()).c_str());
  return outcome.exit_code;
}

}  // namespace tongue::controller
