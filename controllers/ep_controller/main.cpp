// ep_controller --plan FILE [--delay-ms D] [--velocity-factor on|off] [--force-lag-ms T]
//               [common options]
//
// Drives a tongue server with Feldman's lambda model (ep_controller.hpp): every muscle's force
// from its length and velocity through the reflex delay, its threshold moved by the motor plan.
#include <memory>

#include "controller/command_line.hpp"
#include "controller/controller_main.hpp"
#include "ep_controller/ep_controller.hpp"

namespace {

using namespace tongue;

std::unique_ptr<controller::Controller> make(const controller::CommandLine& line) {
  ep_controller::EpSettings settings;
  if (const auto it = line.values.find("--delay-ms"); it != line.values.end()) {
    const double ms = controller::parse_number("--delay-ms", it->second);
    if (ms < 0.0 || ms > 1000.0)
      throw controller::UsageError("--delay-ms must be in [0, 1000] ms, not '" + it->second + "'");
    settings.delay_s = ms * 1e-3;
  }
  if (const auto it = line.values.find("--force-lag-ms"); it != line.values.end()) {
    const double ms = controller::parse_number("--force-lag-ms", it->second);
    if (ms < 0.0 || ms > 10000.0)
      throw controller::UsageError("--force-lag-ms must be in [0, 10000] ms, not '" + it->second +
                                   "'");
    settings.force_lag_s = ms * 1e-3;
  }
  if (const auto it = line.values.find("--velocity-factor"); it != line.values.end()) {
    if (it->second == "on") {
      settings.velocity_factor = true;
    } else if (it->second == "off") {
      settings.velocity_factor = false;
    } else {
      throw controller::UsageError("--velocity-factor must be on or off, not '" + it->second + "'");
    }
  }
  return std::make_unique<ep_controller::EpController>(
      ep_controller::read_motor_plan(line.values.at("--plan")), settings);
}

}  // namespace

int main(int argc, char** argv) {
  controller::ProgramSpec spec;
  spec.name = "ep_controller";
  spec.synopsis = "--plan FILE [--delay-ms D] [--velocity-factor on|off] [--force-lag-ms T]";
  spec.options_usage =
      "  --plan FILE       motor plan: Delta-lambda targets (mm) per muscle or group\n"
      "  --delay-ms D      reflex delay, ms (default 12; at least one step is used)\n"
      "  --velocity-factor on (default) or off: the force's dependence on velocity\n"
      "  --force-lag-ms T  force development: the levels follow the law through a first-order\n"
      "                    lag of T ms (default 100; 0: the bare lambda model)\n";
  spec.options = {"--plan", "--delay-ms", "--velocity-factor", "--force-lag-ms"};
  spec.required_options = {"--plan"};
  spec.make_controller = make;
  return controller::controller_main(argc, argv, spec);
}
