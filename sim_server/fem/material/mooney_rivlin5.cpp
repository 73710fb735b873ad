#include "fem/material/mooney_rivlin5.hpp"

#include <stdexcept>
#include <string>

namespace tongue::fem {

MooneyRivlin5::MooneyRivlin5()
    : MooneyRivlin5(Coefficients{}, bulk_modulus_from_poisson(initial_shear_modulus(Coefficients{}),
                                                              kDefaultPoissonRatio)) {}

MooneyRivlin5::MooneyRivlin5(const Coefficients& c, double bulk_modulus)
    : UncoupledMaterial(bulk_modulus), c_(c) {
  if (!(initial_shear_modulus(c) > 0.0))
    throw std::invalid_argument("mooney_rivlin5: initial shear modulus 2 (c10 + c01) = " +
                                std::to_string(initial_shear_modulus(c)) + " Pa must be positive");
}

InvariantDerivatives MooneyRivlin5::isochoric_derivatives(double I1_bar, double I2_bar) const {
  const double x = I1_bar - 3.0;
  const double y = I2_bar - 3.0;
  InvariantDerivatives w;
  w.energy = c_.c10 * x + c_.c01 * y + c_.c20 * x * x + c_.c11 * x * y + c_.c02 * y * y;
  w.d1 = c_.c10 + 2.0 * c_.c20 * x + c_.c11 * y;
  w.d2 = c_.c01 + c_.c11 * x + 2.0 * c_.c02 * y;
  w.d11 = 2.0 * c_.c20;
  w.d12 = c_.c11;
  w.d22 = 2.0 * c_.c02;
  return w;
}

}  // namespace tongue::fem
