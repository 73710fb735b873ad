#include "controller/control_loop.hpp"

#include <exception>
#include <optional>

#include "common/interrupt.hpp"
#include "controller/control_session.hpp"

namespace tongue::controller {

LoopOutcome run_control_loop(const std::string& program, const CommonOptions& options,
                             Controller& controller) {
  common::InterruptHandlers interrupts;
  const auto stop = [&interrupts]() -> std::optional<std::string> {
    if (!interrupts.raised()) return std::nullopt;
    return std::string("stopped by ") + interrupts.signal_name();
  };
  std::optional<ControlSession> session;
  try {
    session.emplace(program, options, stop);
    if (const Model* model = session->wait_for_model()) {
      controller.start(*model);
      if (const std::optional<std::int64_t> end = controller.last_step())
        session->end_after(*end, " (the controller's last step)");
      while (const std::optional<NewStates> fresh = session->next_states()) {
        for (const State& s : fresh->states) controller.observe(s);
        if (fresh->answer_step) session->answer(controller.command(*fresh->answer_step));
      }
    }
  } catch (const std::exception& e) {
    if (!session) return LoopOutcome{kExitError, std::string("error: ") + e.what(), {}};
    session->fail(e.what());
  }
  return session->outcome();
}

std::string summary_line(const std::string& program, const LoopOutcome& outcome,
                         const CommonOptions& options, const std::string& controller_summary) {
  const LoopCounts& c = outcome.counts;
  std::string s = program + ": " + outcome.reason + "; " + std::to_string(c.states_received) +
                  " states received";
  if (c.states_received > 0)
    s += " (steps " + std::to_string(c.first_step) + "-" + std::to_string(c.last_step) + ")";
  s += ", " + std::to_string(c.activations_sent) + " activations sent (" +
       (options.mode == LoopMode::lockstep ? "lockstep" : "realtime") + "), " +
       std::to_string(c.commands_sent) + " commands sent";
  if (c.repeated_states > 0 || c.activations_resent > 0)
    s += ", " + std::to_string(c.repeated_states) + " repeated states (" +
         std::to_string(c.activations_resent) + " activations sent again)";
  if (c.resets > 0) s += ", " + std::to_string(c.resets) + " server resets";
  if (c.messages_rejected > 0)
    s += ", " + std::to_string(c.messages_rejected) + " messages rejected";
  if (!controller_summary.empty()) s += "; " + controller_summary;
  return s;
}

}  // namespace tongue::controller
