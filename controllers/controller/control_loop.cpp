#include "controller/control_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <deque>
#include <optional>
#include <stdexcept>

#include <unistd.h>

#include "bus/rejection_notice.hpp"
#include "common/interrupt.hpp"
#include "common/number_text.hpp"
#include "common/untrusted_text.hpp"

namespace tongue::controller {
namespace {

constexpr double kFirstDescribe = 0.2;    // s without a model before the first "describe"
constexpr double kLongestDescribe = 1.0;  // s, the interval "describe" backs off to
constexpr double kPollSlice = 0.05;       // s, longest single wait: signals and timeouts are
                                          // looked at least this often

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

int wait_ms(double until, double now) {
  const double left = std::clamp(until - now, 0.0, kPollSlice);
  return static_cast<int>(left * 1e3) + 1;
}

std::string seconds_text(double s) {
  return common::number_text(s) + " s";
}

// The name the activations carry: the program and its process id, unique on the host (the
// default bus never leaves it).
std::string sender_name(const std::string& program) {
  return program + ":" + std::to_string(static_cast<long long>(getpid()));
}

// Characters of a notice's reason shown (a sentence naming a muscle and a step); its other
// strings are names, cut at common::untrusted_text's default.
constexpr std::size_t kReasonShown = 300;

class Loop {
 public:
  Loop(std::string program, const CommonOptions& options, Controller& controller,
       LoopOutcome& outcome)
      : program_(std::move(program)),
        options_(options),
        controller_(controller),
        outcome_(outcome),
        bus_(options.lcm_url, bus::Channels(options.prefix), program_, sender_name(program_)) {}

  void run() {
    const double start = now_seconds();
    if (!wait_for_model(start)) return;
    controller_.start(model_);
    run_states();
  }

 private:
  bool end(int code, std::string reason) {
    outcome_.exit_code = code;
    outcome_.reason = std::move(reason);
    return false;
  }

  bool interrupted() {
    if (!interrupts_.raised()) return false;
    end(kExitInterrupted, std::string("stopped by ") + interrupts_.signal_name());
    return true;
  }

  void poll(int timeout_ms) {
    bus_.poll(timeout_ms);
    outcome_.counts.messages_rejected = bus_.rejected();
  }

  void command(bus::Command c) {
    bus_.send_command(c);
    ++outcome_.counts.commands_sent;
  }

  bool wait_for_model(double start) {
    double next_describe = start + kFirstDescribe;
    double interval = kFirstDescribe;
    while (true) {
      if (interrupted()) return false;
      if (!bus_.models().empty()) {
        model_ = std::move(bus_.models().front());
        bus_.models().pop_front();
        bus_.set_model(model_);
        return true;
      }
      const double now = now_seconds();
      if (now - start > options_.timeout_s)
        return end(kExitTimeout, "no model on " + bus_.channels().model + " at " + bus_.url() +
                                     " within " + seconds_text(options_.timeout_s) +
                                     " (is the server running with --prefix " + options_.prefix +
                                     " on this URL?)");
      if (now >= next_describe) {
        command(bus::Command::describe);
        interval = std::min(2.0 * interval, kLongestDescribe);
        next_describe = now + interval;
      }
      poll(wait_ms(std::min(next_describe, start + options_.timeout_s), now));
    }
  }

  // Later models (answers to describe, another controller's describe) are the first one again:
  // the bus rejects those with other muscles (the controller resolved its names against the
  // first).
  void check_models() { bus_.models().clear(); }

  void run_states() {
    state_deadline_ = now_seconds() + options_.timeout_s;
    last_step_ = options_.max_steps;
    const std::optional<std::int64_t> controller_end = controller_.last_step();
    if (controller_end && (!last_step_ || *controller_end < *last_step_)) {
      last_step_ = controller_end;
      last_step_reason_ = " (the controller's last step)";
    }
    while (true) {
      if (interrupted()) return;
      check_models();
      if (!bus_.states().empty() && !take_states()) return;
      if (!bus_.rejections().empty() && !take_rejections()) return;
      const double now = now_seconds();
      if (now > state_deadline_) {
        const LoopCounts& c = outcome_.counts;
        end(kExitTimeout, c.states_received == 0
                              ? "model received but no state on " + bus_.channels().state +
                                    " within " + seconds_text(options_.timeout_s)
                              : "no state for " + seconds_text(options_.timeout_s) +
                                    " after step " + std::to_string(c.last_step));
        return;
      }
      poll(wait_ms(state_deadline_, now));
    }
  }

  // Feeds the queued states to the controller and answers the latest. False when the loop ends.
  bool take_states() {
    std::deque<State> states;
    states.swap(bus_.states());
    for (const State& s : states)
      if (!observe(s)) return false;
    state_deadline_ = now_seconds() + options_.timeout_s;
    const std::int64_t k = states.back().step;
    if (last_step_ && k >= *last_step_) {
      end(kExitOk, "reached step " + std::to_string(*last_step_) + last_step_reason_);
      return false;
    }
    // A step is computed once. The state of a step already answered again (published again
    // because the answer or the state was lost, or "paused", or another's describe) is answered,
    // in lock-step, with the very message sent for it: the server takes it once.
    if (answered_step_ && *answered_step_ == k && !reset_since_answer_) {
      if (options_.mode == LoopMode::lockstep) {
        bus_.resend_activation();
        ++outcome_.counts.activations_resent;
      }
      return true;
    }
    const MuscleLevels levels = controller_.command(k + 1);
    bus_.send_activation(options_.mode == LoopMode::lockstep ? k + 1 : -1, levels);
    ++outcome_.counts.activations_sent;
    answered_step_ = k;
    reset_since_answer_ = false;
    return true;
  }

  // Rejection notices: one about the last activation sent ends the loop (the server will not
  // take it: the controller's muscles or levels are wrong for this server, or another controller
  // made the step); the first about another sender is shown, for the log. False when the loop
  // ends.
  bool take_rejections() {
    std::deque<Rejection> notices;
    notices.swap(bus_.rejections());
    const std::optional<Activation>& sent = bus_.last_activation();
    for (const Rejection& n : notices) {
      if (sent && bus::is_about(n, *sent))
        return end(kExitRejected, "the server rejected its activation for step " +
                                      std::to_string(n.activation_step) + " (" + sent->sender +
                                      "): " + common::untrusted_text(n.kind) + ": " +
                                      common::untrusted_text(n.reason, kReasonShown));
      if (outcome_.counts.others_rejected++ == 0)
        std::fprintf(stderr, "%s: the server rejected an activation of %s for step %lld: %s: %s\n",
                     program_.c_str(), common::quoted_untrusted(n.sender).c_str(),
                     static_cast<long long>(n.activation_step),
                     common::untrusted_text(n.kind).c_str(),
                     common::untrusted_text(n.reason, kReasonShown).c_str());
    }
    return true;
  }

  // A state of the step last seen, converged, not after a reset: one already fed to the
  // controller, published again (a repeat after a loss, "paused", an answer to "describe").
  bool is_repeat(const State& s) const {
    const LoopCounts& counts = outcome_.counts;
    return counts.states_received > 0 && s.step == counts.last_step && s.converged;
  }

  bool observe(const State& s) {
    LoopCounts& counts = outcome_.counts;
    if (s.num_muscles != model_.num_muscles ||
        s.muscle_lengths.size() != model_.muscle_names.size())
      throw std::runtime_error("the state of step " + std::to_string(s.step) + " has " +
                               std::to_string(s.num_muscles) + " muscles, the model " +
                               std::to_string(model_.num_muscles));
    if (is_repeat(s)) {
      ++counts.repeated_states;
      return true;
    }
    if (counts.states_received > 0 && s.step < counts.last_step) {
      ++counts.resets;
      reset_since_answer_ = true;
      std::fprintf(stderr, "%s: the server went back from step %lld to %lld (reset)\n",
                   program_.c_str(), static_cast<long long>(counts.last_step),
                   static_cast<long long>(s.step));
    }
    if (counts.states_received == 0) counts.first_step = s.step;
    counts.last_step = s.step;
    ++counts.states_received;
    if (!s.converged)
      return end(kExitNotConverged, "the server did not converge at step " +
                                        std::to_string(s.step + 1) + ": " + s.status);
    controller_.observe(s);
    return true;
  }

  const std::string program_;
  const CommonOptions& options_;
  Controller& controller_;
  LoopOutcome& outcome_;
  common::InterruptHandlers interrupts_;
  ControllerBus bus_;
  Model model_;
  double state_deadline_ = 0.0;            // steady-clock s by which the next state must come
  std::optional<std::int64_t> last_step_;  // the loop ends after this step's state
  std::string last_step_reason_ = " (--max-steps)";
  std::optional<std::int64_t> answered_step_;  // the step of the last state answered
  bool reset_since_answer_ = false;
};

}  // namespace

LoopOutcome run_control_loop(const std::string& program, const CommonOptions& options,
                             Controller& controller) {
  LoopOutcome outcome;
  try {
    Loop(program, options, controller, outcome).run();
  } catch (const std::exception& e) {
    outcome.exit_code = kExitError;
    outcome.reason = std::string("error: ") + e.what();
  }
  return outcome;
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
