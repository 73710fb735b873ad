#include "controller/control_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <deque>
#include <optional>
#include <stdexcept>

#include "common/interrupt.hpp"
#include "common/number_text.hpp"

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

class Loop {
 public:
  Loop(std::string program, const CommonOptions& options, Controller& controller,
       LoopOutcome& outcome)
      : program_(std::move(program)),
        options_(options),
        controller_(controller),
        outcome_(outcome),
        bus_(options.lcm_url, bus::Channels(options.prefix), program_) {}

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
    // Each step is answered once: a repeated state (e.g. "paused") would make a stale activation.
    if (answered_step_ && *answered_step_ == k && !reset_since_answer_) return true;
    const MuscleLevels levels = controller_.command(k + 1);
    bus_.send_activation(options_.mode == LoopMode::lockstep ? k + 1 : -1, levels);
    ++outcome_.counts.activations_sent;
    answered_step_ = k;
    reset_since_answer_ = false;
    return true;
  }

  bool observe(const State& s) {
    LoopCounts& counts = outcome_.counts;
    if (s.num_muscles != model_.num_muscles ||
        s.muscle_lengths.size() != model_.muscle_names.size())
      throw std::runtime_error("the state of step " + std::to_string(s.step) + " has " +
                               std::to_string(s.num_muscles) + " muscles, the model " +
                               std::to_string(model_.num_muscles));
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
  if (c.resets > 0) s += ", " + std::to_string(c.resets) + " server resets";
  if (c.messages_rejected > 0)
    s += ", " + std::to_string(c.messages_rejected) + " messages rejected";
  if (!controller_summary.empty()) s += "; " + controller_summary;
  return s;
}

}  // namespace tongue::controller
