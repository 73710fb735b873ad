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

namespace {

// W_iso and its first derivatives at x = I1b - 3, y = I2b - 3, the one formula of the point and
// the batch versions.
struct FirstDerivatives {
  double energy, d1, d2;
};
inline FirstDerivatives first_derivatives(const MooneyRivlin5::Coefficients& c, double x,
                                          double y) {
  return {c.c10 * x + c.c01 * y + c.c20 * x * x + c.c11 * x * y + c.c02 * y * y,
          c.c10 + 2.0 * c.c20 * x + c.c11 * y, c.c01 + c.c11 * x + 2.0 * c.c02 * y};
}

}  // namespace

InvariantDerivatives MooneyRivlin5::isochoric_derivatives(double I1_bar, double I2_bar) const {
  const FirstDerivatives f = first_derivatives(c_, I1_bar - 3.0, I2_bar - 3.0);
  InvariantDerivatives w;
  w.energy = f.energy;
  w.d1 = f.d1;
  w.d2 = f.d2;
  w.d11 = 2.0 * c_.c20;
  w.d12 = c_.c11;
  w.d22 = 2.0 * c_.c02;
  return w;
}

void MooneyRivlin5::isochoric_first_derivatives(int n, const double* __restrict I1_bar,
                                                const double* __restrict I2_bar,
                                                double* __restrict energy, double* __restrict d1,
                                                double* __restrict d2) const {
  const Coefficients c = c_;  // a local copy, which no store through the outputs can change
  for (int p = 0; p < n; ++p) {
    const FirstDerivatives f = first_derivatives(c, I1_bar[p] - 3.0, I2_bar[p] - 3.0);
    energy[p] = f.energy;
    d1[p] = f.d1;
    d2[p] = f.d2;
  }
}

void MooneyRivlin5::isochoric_second_derivatives(int n, const double* __restrict I1_bar,
                                                 const double* __restrict I2_bar,
                                                 double* __restrict energy, double* __restrict d1,
                                                 double* __restrict d2, double* __restrict d11,
                                                 double* __restrict d12,
                                                 double* __restrict d22) const {
  isochoric_first_derivatives(n, I1_bar, I2_bar, energy, d1, d2);
  // A polynomial of degree 2 in the invariants: constant second derivatives.
  for (int p = 0; p < n; ++p) {
    d11[p] = 2.0 * c_.c20;
    d12[p] = c_.c11;
    d22[p] = 2.0 * c_.c02;
  }
}

}  // namespace tongue::fem
