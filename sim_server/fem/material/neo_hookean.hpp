#pragma once
// Uncoupled neo-Hookean law: W_iso = mu/2 (I1b - 3) (Holzapfel 2000, ch. 6).
#include "fem/material/material.hpp"

namespace tongue::fem {

class NeoHookean final : public UncoupledMaterial {
 public:
  // Throws std::invalid_argument unless mu > 0 and K > 0.
  NeoHookean(double shear_modulus, double bulk_modulus);

  std::string name() const override { return "neo_hookean"; }
  double initial_shear_modulus() const override { return mu_; }
  InvariantDerivatives isochoric_derivatives(double I1_bar, double I2_bar) const override;

 private:
  double mu_;
};

}  // namespace tongue::fem
