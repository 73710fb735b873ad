#pragma once
// How a server runs (its mode, silence rule, published nodes, limits and run file) and how it
// ended (the process exit status); the loop's behaviour under each is in server_loop.hpp.
#include <cstdint>
#include <optional>
#include <string>

#include "common/exit_code.hpp"
#include "server/node_selection.hpp"

namespace tongue::server {

enum class Mode { lockstep, fast, realtime };
enum class OnSilence { hold, stop, decay };  // decay: real-time mode only

struct ServerOptions {
  Mode mode = Mode::lockstep;
  int timeout_ms = 1000;  // lock-step: silence before a report (and a stop with OnSilence::stop)
  // Lock-step: accepted activation messages tagged k + 1 that make step k + 1 (one per
  // controller, each naming its own muscles). Other modes: 1.
  int controllers = 1;
  // Lock-step: the state of step k is published again repeat_ms after it went out when the
  // activations for k + 1 have not all come, then after twice that interval, four times, ...
  // (at most timeout_ms apart), at most repeats times (StateRepeater); repeat_ms 0: never. The
  // defaults: 10 repeats over 6.55 s (50, 100, 200, 400, 800 ms, then every 1 s).
  int repeat_ms = 50;
  int repeats = 10;
  OnSilence on_silence = OnSilence::hold;
  double silence_s = 0.5;  // real-time: silence before hold / decay / stop [s]
  Nodes nodes = Nodes::all;
  int publish_every = 1;  // fast and real-time: publish the state every this many steps
  std::optional<std::int64_t> max_steps;  // end (exit 0) once this step is reached
  std::string output;                     // run file; empty: none
};

// How the loop ended, the process exit status (common/exit_code.hpp): kExitOk after shutdown or
// max_steps, kExitError for an exception (e.g. the run file cannot be written),
// kExitNotConverged when a step or the settling failed even after cuts, kExitSilence for
// on_silence stop, kExitInterrupted when stop_requested said so.
using ExitStatus = common::ExitCode;

}  // namespace tongue::server
