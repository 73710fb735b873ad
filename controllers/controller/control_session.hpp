#pragma once
// The controller's side of the protocol with one tongue server, driven from outside: the caller
// asks for the model, then for the states to answer, and answers them (control_loop.hpp says what
// happens at each point). run_control_loop drives it for a Controller; the Python bus client
// drives it from a for-loop.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "controller/command_line.hpp"
#include "controller/control_loop.hpp"
#include "controller/controller_bus.hpp"

namespace tongue::controller {

// New states in the order received, each to be observed; when answer_step is set, the caller
// answers with the levels for that step (the last state's step + 1) before asking for more.
struct NewStates {
  std::vector<State> states;
  std::optional<std::int64_t> answer_step;  // nullopt: the session ended after these states
};

class ControlSession {
 public:
  // Why to stop now (e.g. "stopped by SIGINT"), or nullopt; asked between waits on the bus, which
  // last at most 50 ms.
  using StopCheck = std::function<std::optional<std::string>()>;

  // Starts receiving on the server's channels. Throws like ControllerBus; the methods below throw
  // std::runtime_error when LCM fails or a state does not fit the model.
  ControlSession(std::string program, const CommonOptions& options, StopCheck stop);

  // Waits for the model, sending "describe" while none comes. nullptr when the session ended
  // (outcome() says why).
  const Model* wait_for_model();
  // Ends the session after the state of step (when before --max-steps); reason follows "reached
  // step N" in the outcome, e.g. " (the controller's last step)".
  void end_after(std::int64_t step, const std::string& reason);
  // Waits for new states. nullopt when the session ended and there is nothing more to observe.
  // A repeated state of the step last answered is answered here with the message sent for it.
  std::optional<NewStates> next_states();
  // The levels for the step next_states() asked for. Throws std::logic_error when none is asked.
  void answer(const MuscleLevels& levels);

  // Ends the session with kExitError: what the caller failed at (the controller's input did not
  // fit the model, LCM failed), reason as "error: <what>".
  void fail(const std::string& what);

  bool ended() const { return ended_; }
  const LoopOutcome& outcome() const { return outcome_; }
  const CommonOptions& options() const { return options_; }

 private:
  void end(int code, std::string reason);
  bool stopped();
  void poll(int timeout_ms);
  bool is_repeat(const State& s) const;
  // Counts s; false when it ends the session (it did not converge).
  bool take(const State& s);
  // Handles the queued rejection notices; false when one ends the session.
  bool take_rejections();
  // The queued states as NewStates, or nullopt when they were all repeats (answered here).
  std::optional<NewStates> take_states();

  const std::string program_;
  const CommonOptions options_;
  StopCheck stop_;
  LoopOutcome outcome_;
  bool ended_ = false;
  ControllerBus bus_;
  Model model_;
  bool have_model_ = false;
  double state_deadline_ = 0.0;            // steady-clock s by which the next state must come
  std::optional<std::int64_t> last_step_;  // the session ends after this step's state
  std::string last_step_reason_ = " (--max-steps)";
  std::optional<std::int64_t> pending_step_;   // asked for and not yet answered
  std::optional<std::int64_t> answered_step_;  // the step of the last state answered
  bool reset_since_answer_ = false;
};

}  // namespace tongue::controller
