#pragma once
// Small-strain isotropic linear elasticity, for scenes that trade accuracy for speed:
//   eps = sym(F - I), W = lambda/2 (tr eps)^2 + mu eps:eps, P = lambda tr(eps) I + 2 mu eps.
// Not objective under finite rotations (use only for small rotations) and not uncoupled.
#include "fem/material/material.hpp"

namespace tongue::fem {

class LinearElastic final : public Material {
 public:
  // Throws std::invalid_argument unless mu > 0 and K > 0.
  LinearElastic(double shear_modulus, double bulk_modulus);
  // From Young's modulus E > 0 and Poisson's ratio nu in (-1, 0.5).
  static LinearElastic from_youngs_modulus(double youngs_modulus, double poisson_ratio);

  std::string name() const override { return "linear"; }
  PointResponse response(const Mat3& F, bool with_tangent = true) const override;
  double initial_shear_modulus() const override { return mu_; }
  double bulk_modulus() const override { return K_; }
  double lame_lambda() const { return K_ - 2.0 * mu_ / 3.0; }

  // The constant tangent lambda d_iJ d_kL + mu (d_ik d_JL + d_iL d_kJ) on the flattening.
  static Mat9 isotropic_tangent(double shear_modulus, double lame_lambda);

 private:
  double mu_, K_;
  Mat9 tangent_;
};

}  // namespace tongue::fem
