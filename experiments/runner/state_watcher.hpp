#pragma once
// The runner's view of a run on the bus: the server's states, for its readiness (state 0), the
// progress and the closed loop's pace.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include <lcm/lcm-cpp.hpp>

#include "bus/bus_receiver.hpp"
#include "bus/lcm_url.hpp"
#include "bus/messages.hpp"
#include "common/rate_limited_reporter.hpp"

namespace tongue::runner {

class StateWatcher {
 public:
  // Receives on channel on the bus at url, every message through the bus's size limit and
  // checked decoder (a forged state is reported, not fatal). Throws std::runtime_error when the
  // bus cannot be opened.
  StateWatcher(const std::string& url, const std::string& channel);
  StateWatcher(const StateWatcher&) = delete;
  StateWatcher& operator=(const StateWatcher&) = delete;

  // Waits at most timeout_ms for a state, then takes the states already there: the runner
  // judges a controller that has ended by the last state, which must not wait in the queue
  // behind others (repeated states, a describe's answer).
  void poll(int timeout_ms);
  std::optional<std::int64_t> last_step() const { return last_step_; }
  // Steps per wall second between the first and the last state received (0: too few).
  double steps_per_second() const;
  bool any_unconverged() const { return unconverged_; }

 private:
  using Clock = std::chrono::steady_clock;

  void on_state(const tongue_lcm::lcmt_tongue_state& s);

  bus::LcmUrl url_;
  lcm::LCM lcm_;
  bus::BusReceiver receiver_;
  common::RateLimitedReporter reports_{1.0};
  std::optional<std::int64_t> last_step_;
  bool driving_ = false;
  std::int64_t first_step_ = 0;
  Clock::time_point first_at_, last_at_;
  bool unconverged_ = false;
};

}  // namespace tongue::runner
