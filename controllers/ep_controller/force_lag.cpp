#include "ep_controller/force_lag.hpp"

#include <cmath>
#include <stdexcept>

namespace tongue::ep_controller {

ForceLag::ForceLag(std::size_t size, double tau_s, double dt_s)
    : tau_s_(tau_s), dt_s_(dt_s), y_(size, 0.0), u_(size, 0.0) {
  if (!(tau_s >= 0.0) || !std::isfinite(tau_s))
    throw std::invalid_argument("the force lag's time constant must be a finite number >= 0 s");
  if (!(dt_s > 0.0)) throw std::invalid_argument("the force lag's step must be > 0 s");
}

const std::vector<double>& ForceLag::update(std::int64_t step, const std::vector<double>& u) {
  if (u.size() != y_.size()) throw std::invalid_argument("ForceLag::update: wrong input size");
  std::int64_t steps = 1;
  if (last_step_ && step > *last_step_) {
    steps = step - *last_step_;
  } else if (last_step_) {
    y_.assign(y_.size(), 0.0);  // reset: the server starts from 0 again
    u_.assign(u_.size(), 0.0);
  }
  last_step_ = step;
  if (tau_s_ == 0.0) {
    y_ = u;
    return y_;
  }
  const double x = static_cast<double>(steps) * dt_s_ / tau_s_;  // h / tau
  const double one_minus_e = -std::expm1(-x);                    // 1 - E, exact for small x
  const double e = 1.0 - one_minus_e;
  const double b = 1.0 - one_minus_e / x;
  const double a = one_minus_e - b;  // (tau / h)(1 - E) - E = 1 - E - b
  for (std::size_t i = 0; i < y_.size(); ++i) y_[i] = e * y_[i] + a * u_[i] + b * u[i];
  u_ = u;
  return y_;
}

}  // namespace tongue::ep_controller
