#include "fem/material/exponential.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace tongue::fem {

Exponential::Exponential()
    : Exponential(kDefaultA, kDefaultB,
                  bulk_modulus_from_poisson(2.0 * kDefaultA, kDefaultPoissonRatio)) {}

Exponential::Exponential(double a, double b, double bulk_modulus)
    : UncoupledMaterial(bulk_modulus), a_(a), b_(b) {
  if (!(a > 0.0) || !std::isfinite(a))
    throw std::invalid_argument("exponential: a must be positive, got " + std::to_string(a));
  // b -> 0 is the neo-Hookean limit but divides by zero in W; b < 0 softens without bound.
  if (!(b > 0.0) || !std::isfinite(b))
    throw std::invalid_argument("exponential: b must be positive, got " + std::to_string(b));
}

InvariantDerivatives Exponential::isochoric_derivatives(double I1_bar, double /*I2_bar*/) const {
  const double x = I1_bar - 3.0;
  const double e = std::exp(b_ * x);
  InvariantDerivatives w;
  // expm1 keeps W accurate near the rest state, where b x is tiny.
  w.energy = (a_ / b_) * std::expm1(b_ * x);
  w.d1 = a_ * e;
  w.d11 = a_ * b_ * e;
  return w;
}

}  // namespace tongue::fem
