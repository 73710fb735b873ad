// sequence_player --schedule FILE [common options]
//
// Sends the activation levels of a schedule file (activation_sequence.hpp) to a tongue server,
// step by step: the levels at (k + 1) dt for step k + 1.
#include <memory>

#include "controller/controller_main.hpp"
#include "sequence_player/sequence_player.hpp"

namespace {

using namespace tongue;

std::unique_ptr<controller::Controller> make(const controller::CommandLine& line) {
  return std::make_unique<sequence_player::SequencePlayer>(
      sequence_player::read_sequence(line.values.at("--schedule")));
}

}  // namespace

int main(int argc, char** argv) {
  controller::ProgramSpec spec;
  spec.name = "sequence_player";
  spec.synopsis = "--schedule FILE";
  spec.options_usage =
      "  --schedule FILE   steps and ramps of activation per muscle or group (level in [0, 1]\n"
      "                    of F_max, or force in N), times in s; duration: ends the run\n";
  spec.options = {"--schedule"};
  spec.required_options = {"--schedule"};
  spec.make_controller = make;
  return controller::controller_main(argc, argv, spec);
}
