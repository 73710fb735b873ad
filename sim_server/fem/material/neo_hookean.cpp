#include "fem/material/neo_hookean.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace tongue::fem {

NeoHookean::NeoHookean(double shear_modulus, double bulk_modulus)
    : UncoupledMaterial(bulk_modulus), mu_(shear_modulus) {
  if (!(shear_modulus > 0.0) || !std::isfinite(shear_modulus))
    throw std::invalid_argument("neo_hookean: shear modulus must be positive, got " +
                                std::to_string(shear_modulus));
}

InvariantDerivatives NeoHookean::isochoric_derivatives(double I1_bar, double /*I2_bar*/) const {
  InvariantDerivatives w;
  w.energy = 0.5 * mu_ * (I1_bar - 3.0);
  w.d1 = 0.5 * mu_;
  return w;
}

}  // namespace tongue::fem
