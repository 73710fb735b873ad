#pragma once
// Exponential law in I1b, the source law of the tongue model (Gerard et al. 2003 sec. III.2;
// docs/physics.md):
//   W_iso = (a / b) (exp(b (I1b - 3)) - 1); mu0 = 2 a.
#include "fem/material/material.hpp"

namespace tongue::fem {

class Exponential final : public UncoupledMaterial {
 public:
  static constexpr double kDefaultA = 2500.0;  // [Pa]
  static constexpr double kDefaultB = 0.2526;  // [-]
  static constexpr double kDefaultPoissonRatio = 0.49;

  // Default a, b; K from nu = 0.49 and mu0 = 2 a.
  Exponential();
  // Throws std::invalid_argument unless a > 0, b > 0 and K > 0.
  Exponential(double a, double b, double bulk_modulus);

  std::string name() const override { return "exponential"; }
  double initial_shear_modulus() const override { return 2.0 * a_; }
  InvariantDerivatives isochoric_derivatives(double I1_bar, double I2_bar) const override;
  double a() const { return a_; }
  double b() const { return b_; }

 private:
  double a_, b_;
};

}  // namespace tongue::fem
