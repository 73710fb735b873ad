// replay --log RUN.h5 [common options]
//
// Republishes the activations of a run file in lock-step (row k + 1 for step k + 1), so that a
// fresh server on the same scene repeats the logged run.
#include <memory>

#include "controller/controller_main.hpp"
#include "replay/replayer.hpp"

namespace {

using namespace tongue;

std::unique_ptr<controller::Controller> make(const controller::CommandLine& line) {
  return std::make_unique<replay::Replayer>(
      replay::read_recorded_activations(line.values.at("--log")));
}

}  // namespace

int main(int argc, char** argv) {
  controller::ProgramSpec spec;
  spec.name = "replay";
  spec.synopsis = "--log RUN.h5";
  spec.options_usage =
      "  --log RUN.h5      run file (sim_server or sim_batch, every step logged) whose\n"
      "                    /activations are sent again, row k+1 for step k+1\n";
  spec.options = {"--log"};
  spec.required_options = {"--log"};
  spec.make_controller = make;
  return controller::controller_main(argc, argv, spec);
}
