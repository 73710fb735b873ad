#pragma once
// Force development: the levels the controller sends follow the lambda model's levels through a
// first-order lag, the activation dynamics of Hill-type muscle models (Zajac 1989: force builds
// up and decays over tens of milliseconds after the neural command changes):
//
//   tau dy/dt = u - y,   discretized exactly for u moving linearly from one update's input to
//   the next over h = n dt (a first-order hold), with E = exp(-h / tau):
//   y_(k+n) = E y_k + a u_k + b u_(k+n),   a = (tau / h)(1 - E) - E,   b = 1 - (tau / h)(1 - E)
//
// (Franklin, Powell & Workman, "Digital Control of Dynamic Systems", 3rd ed. 1998, sec. 6.3.2,
// the triangle-hold equivalent). a, b >= 0 and E + a + b = 1, so y stays between its inputs.
// The input is the law's level at the end of each step, which the controller's lambda ramps and
// delayed feedback move continuously: holding it over the step instead (the zero-order hold)
// makes a first-order error in the step, a lag of half a step on every force (at dt 4 ms the
// /ai/ closed loop's RMS error against its dt = 0.1 ms run was 0.32 mm with that hold).
//
// Not part of the lambda model (lambda_model.hpp); the controller adds it (tau 100 ms by
// default, 0 turns it off) because on the 3D tongue the bare law, whose gain dM/dA =
// rho c exp(c A) grows with the stretch, is unstable with any reflex delay: at the /ai/ commands
// its levels jump between 0 and 1 at about 36 Hz (with a delay of 4 or 12 ms alike). With the lag
// the levels are smooth; the residual oscillation of the /i/ posture (12 ms delay) shrinks as tau
// grows: root x peak to peak over the last 0.1 s of 0.5 s, 3.4 mm at 50 ms, 1.4 at 70, 0.8 at
// 100 (the default: the smallest round value under 1 mm), 0.5 at 150; the posture reached is the
// same (root +9 mm). A shorter delay needs less (8 ms: 0.1 mm at tau 50 ms), a longer one more.
#include <cstdint>
#include <optional>
#include <vector>

namespace tongue::ep_controller {

class ForceLag {
 public:
  // tau_s >= 0 (0: no lag, the output is the input); dt_s > 0, the step.
  ForceLag(std::size_t size, double tau_s, double dt_s);

  // The output for step `step` given the input u at that step, the input having moved linearly
  // from the previous update's (0 before the first). A step not after the previous one (a
  // server reset) starts again from 0, as the server's levels do.
  const std::vector<double>& update(std::int64_t step, const std::vector<double>& u);
  const std::vector<double>& output() const { return y_; }

 private:
  double tau_s_, dt_s_;
  std::vector<double> y_;
  std::vector<double> u_;  // the previous update's input
  std::optional<std::int64_t> last_step_;
};

}  // namespace tongue::ep_controller
