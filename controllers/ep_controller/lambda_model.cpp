#include "ep_controller/lambda_model.hpp"

#include <algorithm>
#include <cmath>

namespace tongue::ep_controller {

double stretch_beyond_threshold_mm(double length_mm, double lambda_mm, double velocity_mm_s,
                                   const LambdaConstants& k) {
  return std::max(0.0, length_mm - lambda_mm + k.mu_s * velocity_mm_s);
}

double exponential_force(double stretch_mm, double rho_n, const LambdaConstants& k) {
  // expm1 keeps the small forces just above threshold accurate.
  return rho_n * std::expm1(k.c_per_mm * stretch_mm);
}

double velocity_factor(double relative_velocity_per_s, const LambdaConstants& k) {
  const double r = relative_velocity_per_s;
  return std::max(0.0, k.f1 + k.f2 * std::atan(k.f3 + k.f4 * r) + k.f5 * r);
}

double force_level(double force_n, double max_force_n) {
  return std::clamp(force_n / max_force_n, 0.0, 1.0);
}

MuscleCommand muscle_command(const MuscleLaw& law, double lambda_mm, double length_mm,
                             double velocity_mm_s, bool use_velocity_factor,
                             const LambdaConstants& k) {
  MuscleCommand c;
  c.stretch_mm = stretch_beyond_threshold_mm(length_mm, lambda_mm, velocity_mm_s, k);
  c.force_n = exponential_force(c.stretch_mm, law.rho_n, k);
  if (use_velocity_factor) c.force_n *= velocity_factor(velocity_mm_s / law.rest_length_mm, k);
  c.level = force_level(c.force_n, law.max_force_n);
  return c;
}

}  // namespace tongue::ep_controller
