#pragma once
// Five-parameter Mooney-Rivlin law, the tongue law of Gérard et al. 2003:
//   W_iso = c10 (I1b-3) + c01 (I2b-3) + c20 (I1b-3)^2 + c11 (I1b-3)(I2b-3) + c02 (I2b-3)^2.
// Negative c01 and c11 make W_iso non-convex at large strain; the tests only check consistency.
#include "fem/material/material.hpp"

namespace tongue::fem {

class MooneyRivlin5 final : public UncoupledMaterial {
 public:
  struct Coefficients {  // [Pa]; defaults from Gérard et al. 2003
    double c10 = 4367.0;
    double c01 = -1908.0;
    double c20 = 2077.0;
    double c11 = -1851.0;
    double c02 = 530.0;
  };

  // The paper's law: default coefficients, K from nu = 0.49 and mu0 (K = 244.26 kPa).
  MooneyRivlin5();
  // Throws std::invalid_argument unless mu0 = 2 (c10 + c01) > 0 and K > 0.
  MooneyRivlin5(const Coefficients& c, double bulk_modulus);

  // Small-strain shear modulus mu0 = 2 (c10 + c01).
  static double initial_shear_modulus(const Coefficients& c) { return 2.0 * (c.c10 + c.c01); }

  std::string name() const override { return "mooney_rivlin5"; }
  double initial_shear_modulus() const override { return initial_shear_modulus(c_); }
  InvariantDerivatives isochoric_derivatives(double I1_bar, double I2_bar) const override;
  void isochoric_first_derivatives(int n, const double* I1_bar, const double* I2_bar,
                                   double* energy, double* d1, double* d2) const override;
  void isochoric_second_derivatives(int n, const double* I1_bar, const double* I2_bar,
                                    double* energy, double* d1, double* d2, double* d11,
                                    double* d12, double* d22) const override;
  const Coefficients& coefficients() const { return c_; }

 private:
  Coefficients c_;
};

}  // namespace tongue::fem
