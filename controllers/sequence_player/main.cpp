// sequence_player --schedule FILE [common options]
//
// Sends the activation levels of a schedule file (activation_sequence.hpp) to a tongue server,
// step by step: the levels at (k + 1) dt for step k + 1.
#include <memory>

#include "common/controller_main.hpp"
#include "sequence_player/sequence_player.hpp"

namespace {

using namespace tongue::controllers;

std::unique_ptr<Controller> make(const CommandLine& line) {
  return std::make_unique<sequence::SequencePlayer>(
      sequence::read_sequence(line.values.at("--schedule")));
}

}  // namespace

int main(int argc, char** argv) {
  ProgramSpec spec;
  spec.name = "sequence_player";
  spec.synopsis = "--schedule FILE";
  spec.options_usage =
      "  --schedule FILE   steps and ramps of activation per muscle or group (level in [0, 1]\n"
      "                    of F_max, or force in N), times in s; duration: ends the run\n";
  spec.options = {"--schedule"};
  spec.required_options = {"--schedule"};
  spec.make_controller = make;
  return controller_main(argc, argv, spec);
}
