#pragma once
// Lock-step over a bus that loses datagrams (UDP multicast drops them when a socket buffer is
// full): when the activations for step k + 1 are late, the state of step k is published again, so
// that a lost state or a lost activation costs a delay, not the run. The first repeat comes
// first_ms after the state went out, each further one after twice the previous interval (a
// controller that is merely slow is not flooded) but at most longest_ms, and at most max_repeats
// per state; then the silence rule (--timeout-ms, --on-silence) alone applies. Controllers answer
// a repeated state with the very message they sent for it, which the server takes once
// (RoundSenders); each repeat also restarts a controller's wait for the server (--timeout-s).
#include <cstdint>
#include <optional>

namespace tongue::server {

class StateRepeater {
 public:
  // first_ms 0: never repeat. Throws std::invalid_argument for a negative first_ms or
  // max_repeats, or longest_ms below first_ms.
  StateRepeater(int first_ms, int max_repeats, int longest_ms);

  // A state went out at steady-clock now [s] (a new step, state 0, a reset, a resume): its
  // repeats start over.
  void restart(double now);
  // True once per repeat when its time (steady-clock s) has come; the next one is then planned.
  bool due(double now);
  // Steady-clock s of the next repeat; nullopt when none is left.
  std::optional<double> next() const;
  // Repeats made since construction.
  std::int64_t total() const { return total_; }

 private:
  double first_s_;
  int max_repeats_;
  double longest_s_;
  int left_ = 0;           // repeats left for the current state
  double interval_s_ = 0;  // until the next one
  double next_s_ = 0;      // steady-clock s of the next one
  std::int64_t total_ = 0;
};

}  // namespace tongue::server
