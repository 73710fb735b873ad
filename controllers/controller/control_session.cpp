#include "controller/control_session.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <deque>
#include <stdexcept>
#include <utility>

#include <unistd.h>

#include "bus/rejection_notice.hpp"
#include "common/number_text.hpp"
#include "common/untrusted_text.hpp"

namespace tongue::controller {
namespace {

constexpr double kFirstDescribe = 0.2;    // s without a model before the first "describe"
constexpr double kLongestDescribe = 1.0;  // s, the interval "describe" backs off to
constexpr double kPollSlice = 0.05;       // s, longest single wait: stop requests and timeouts
                                          // are looked at least this often

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

}  // namespace

ControlSession::ControlSession(std::string program, const CommonOptions& options, StopCheck stop)
    : program_(std::move(program)),
      options_(options),
      stop_(std::move(stop)),
      bus_(options.lcm_url, bus::Channels(options.prefix), program_, sender_name(program_)),
      last_step_(options.max_steps) {}

void ControlSession::end(int code, std::string reason) {
  ended_ = true;
  pending_step_.reset();
  outcome_.exit_code = code;
  outcome_.reason = std::move(reason);
}

void ControlSession::fail(const std::string& what) {
  end(kExitError, "error: " + what);
}

bool ControlSession::stopped() {
  if (ended_) return true;
  if (!stop_) return false;
  std::optional<std::string> reason = stop_();
  if (!reason) return false;
  end(kExitInterrupted, std::move(*reason));
  return true;
}

void ControlSession::poll(int timeout_ms) {
  bus_.poll(timeout_ms);
  outcome_.counts.messages_rejected = bus_.rejected();
}

const Model* ControlSession::wait_for_model() {
  if (have_model_) return &model_;
  const double start = now_seconds();
  double next_describe = start + kFirstDescribe;
  double interval = kFirstDescribe;
  while (!stopped()) {
    if (!bus_.models().empty()) {
      model_ = std::move(bus_.models().front());
      bus_.models().pop_front();
      bus_.set_model(model_);
      have_model_ = true;
      return &model_;
    }
    const double now = now_seconds();
    if (now - start > options_.timeout_s) {
      end(kExitTimeout, "no model on " + bus_.channels().model + " at " + bus_.url() + " within " +
                            seconds_text(options_.timeout_s) +
                            " (is the server running with --prefix " + options_.prefix +
                            " on this URL?)");
      return nullptr;
    }
    if (now >= next_describe) {
      bus_.send_command(bus::Command::describe);
      ++outcome_.counts.commands_sent;
      interval = std::min(2.0 * interval, kLongestDescribe);
      next_describe = now + interval;
    }
    poll(wait_ms(std::min(next_describe, start + options_.timeout_s), now));
  }
  return nullptr;
}

void ControlSession::end_after(std::int64_t step, const std::string& reason) {
  if (last_step_ && *last_step_ <= step) return;
  last_step_ = step;
  last_step_reason_ = reason;
}

std::optional<NewStates> ControlSession::next_states() {
  if (pending_step_)
    throw std::logic_error("the states of step " + std::to_string(*pending_step_ - 1) +
                           " are not answered yet");
  if (!have_model_ && !ended_ && !wait_for_model()) return std::nullopt;
  // The first wait for a state starts here, not at the model: the caller may take its time
  // to set up in between.
  if (state_deadline_ == 0.0) state_deadline_ = now_seconds() + options_.timeout_s;
  while (!stopped()) {
    // Later models (answers to describe, another controller's describe) are the first one again:
    // the bus rejects those with other muscles (the caller resolved its names against the first).
    bus_.models().clear();
    if (!bus_.states().empty())
      if (std::optional<NewStates> states = take_states()) return states;
    if (ended_) return std::nullopt;
    if (!bus_.rejections().empty() && !take_rejections()) return std::nullopt;
    const double now = now_seconds();
    if (now > state_deadline_) {
      const LoopCounts& c = outcome_.counts;
      end(kExitTimeout, c.states_received == 0
                            ? "model received but no state on " + bus_.channels().state +
                                  " within " + seconds_text(options_.timeout_s)
                            : "no state for " + seconds_text(options_.timeout_s) + " after step " +
                                  std::to_string(c.last_step));
      return std::nullopt;
    }
    poll(wait_ms(state_deadline_, now));
  }
  return std::nullopt;
}

std::optional<NewStates> ControlSession::take_states() {
  std::deque<State> queued;
  queued.swap(bus_.states());
  NewStates fresh;
  for (State& s : queued) {
    if (is_repeat(s)) {
      ++outcome_.counts.repeated_states;
      continue;
    }
    if (!take(s)) return fresh;  // the session ended: the states before s are still observed
    fresh.states.push_back(std::move(s));
  }
  state_deadline_ = now_seconds() + options_.timeout_s;
  const std::int64_t k = queued.back().step;
  if (last_step_ && k >= *last_step_) {
    end(kExitOk, "reached step " + std::to_string(*last_step_) + last_step_reason_);
    return fresh;
  }
  // A step is computed once. The state of a step already answered again (published again
  // because the answer or the state was lost, or "paused", or another's describe) is answered,
  // in lock-step, with the very message sent for it: the server takes it once.
  if (answered_step_ && *answered_step_ == k && !reset_since_answer_) {
    if (options_.mode == LoopMode::lockstep) {
      bus_.resend_activation();
      ++outcome_.counts.activations_resent;
    }
    if (fresh.states.empty()) return std::nullopt;
    return fresh;
  }
  pending_step_ = k + 1;
  fresh.answer_step = k + 1;
  return fresh;
}

void ControlSession::answer(const MuscleLevels& levels) {
  if (!pending_step_) throw std::logic_error("no state waits for an answer");
  const std::int64_t step = *pending_step_;
  bus_.send_activation(options_.mode == LoopMode::lockstep ? step : -1, levels);
  ++outcome_.counts.activations_sent;
  answered_step_ = step - 1;
  reset_since_answer_ = false;
  pending_step_.reset();
}

// Rejection notices: one about the last activation sent ends the session (the server will not
// take it: the controller's muscles or levels are wrong for this server, or another controller
// made the step); the first about another sender is shown, for the log.
bool ControlSession::take_rejections() {
  std::deque<Rejection> notices;
  notices.swap(bus_.rejections());
  const std::optional<Activation>& sent = bus_.last_activation();
  for (const Rejection& n : notices) {
    if (sent && bus::is_about(n, *sent)) {
      end(kExitRejected, "the server rejected its activation for step " +
                             std::to_string(n.activation_step) + " (" + sent->sender +
                             "): " + common::untrusted_text(n.kind) + ": " +
                             common::untrusted_text(n.reason, kReasonShown));
      return false;
    }
    if (outcome_.counts.others_rejected++ == 0)
      std::fprintf(stderr, "%s: the server rejected an activation of %s for step %lld: %s: %s\n",
                   program_.c_str(), common::quoted_untrusted(n.sender).c_str(),
                   static_cast<long long>(n.activation_step),
                   common::untrusted_text(n.kind).c_str(),
                   common::untrusted_text(n.reason, kReasonShown).c_str());
  }
  return true;
}

// A state of the step last seen, converged, not after a reset: one already observed, published
// again (a repeat after a loss, "paused", an answer to "describe").
bool ControlSession::is_repeat(const State& s) const {
  const LoopCounts& counts = outcome_.counts;
  return counts.states_received > 0 && s.step == counts.last_step && s.converged;
}

bool ControlSession::take(const State& s) {
  LoopCounts& counts = outcome_.counts;
  if (s.num_muscles != model_.num_muscles || s.muscle_lengths.size() != model_.muscle_names.size())
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
  if (!s.converged) {
    end(kExitNotConverged,
        "the server did not converge at step " + std::to_string(s.step + 1) + ": " + s.status);
    return false;
  }
  return true;
}

}  // namespace tongue::controller
