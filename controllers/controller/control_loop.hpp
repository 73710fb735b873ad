#pragma once
// The loop every controller program runs against one tongue server (lock-step protocol: README
// "Running the server"), a ControlSession (control_session.hpp) driven for a Controller:
//
// 1. Wait for the model on <prefix>MODEL. Without one within 200 ms, send "describe" on
//    <prefix>COMMAND, again after 400 ms, 800 ms, then every second (a server still settling
//    answers them all at once, so they are spaced out rather than flooded).
// 2. Wait for states on <prefix>STATE. A controller started after the server has missed the
//    state a lock-step server waits on; the server's answer to "describe" (model, then current
//    state) brings it.
// 3. Every new state goes to the controller (observe); the latest one, step k, is answered with
//    the controller's levels for step k + 1, tagged k + 1 (lockstep) or -1 (realtime: the server
//    holds it). A step is computed once unless the server was reset meanwhile (the step went
//    down): a repeated state (the same step again: the server publishes it again when the answer
//    is late, after a loss; "paused"; an answer to "describe") is not observed again, and in
//    lock-step it is answered with the very message sent for it, which the server takes once.
// 4. The loop ends (exit 0) after the state of step N = min(--max-steps, the controller's last
//    step), sending nothing for later steps; on SIGINT or SIGTERM (exit 130); with exit 4 when
//    the model, the first state or any later state does not come within --timeout-s; with exit 2
//    when the server publishes an unconverged step (it stops there); with exit 5 when a rejection
//    notice on <prefix>REJECTION names the last activation sent (the reason is printed; notices
//    for other senders are counted, the first printed); with exit 1 on a bus error or an input
//    that does not fit the model (common/exit_code.hpp). A one-line summary goes to stderr in
//    every case.
#include <cstdint>
#include <string>

#include "common/exit_code.hpp"
#include "controller/command_line.hpp"
#include "controller/controller.hpp"

namespace tongue::controller {

using common::kExitError;
using common::kExitInterrupted;
using common::kExitNotConverged;
using common::kExitOk;
using common::kExitRejected;
using common::kExitTimeout;

struct LoopCounts {
  std::int64_t states_received = 0;  // new states (repeats not counted)
  std::int64_t repeated_states = 0;  // states of the step last seen again
  std::int64_t activations_sent = 0;
  std::int64_t activations_resent = 0;  // the last one again, answering a repeated state
  std::int64_t others_rejected = 0;     // rejection notices about other senders' activations
  std::int64_t commands_sent = 0;       // describe
  std::int64_t first_step = -1;         // of the states received; -1: none
  std::int64_t last_step = -1;
  int resets = 0;  // times the server's step went down
  // States, models and notices received and rejected (undecodable, or not fitting the model).
  std::int64_t messages_rejected = 0;
};

struct LoopOutcome {
  int exit_code = kExitOk;
  std::string reason;  // why the loop ended, e.g. "reached step 30 (--max-steps)"
  LoopCounts counts;
};

// Runs the loop for controller on the bus of options. A bus error, or an InputError from
// controller.start (its input does not fit the model), ends it with kExitError and the message
// as the reason.
// program names the controller in the messages it prints.
LoopOutcome run_control_loop(const std::string& program, const CommonOptions& options,
                             Controller& controller);

// The summary line: "<program>: <reason>; <n> states received (steps a-b), <m> activations sent
// (lockstep), <c> commands sent[, <r> repeated states (<s> activations sent again)][, <n> server
// resets][, <j> messages rejected][; <controller summary>]".
std::string summary_line(const std::string& program, const LoopOutcome& outcome,
                         const CommonOptions& options, const std::string& controller_summary);

}  // namespace tongue::controller
