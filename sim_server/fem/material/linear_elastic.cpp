#include "fem/material/linear_elastic.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace tongue::fem {

LinearElastic::LinearElastic(double shear_modulus, double bulk_modulus)
    : mu_(shear_modulus), K_(bulk_modulus) {
  if (!(shear_modulus > 0.0) || !std::isfinite(shear_modulus))
    throw std::invalid_argument("linear: shear modulus must be positive, got " +
                                std::to_string(shear_modulus));
  if (!(bulk_modulus > 0.0) || !std::isfinite(bulk_modulus))
    throw std::invalid_argument("linear: bulk modulus must be positive, got " +
                                std::to_string(bulk_modulus));
  tangent_ = isotropic_tangent(mu_, lame_lambda());
}

LinearElastic LinearElastic::from_youngs_modulus(double youngs_modulus, double poisson_ratio) {
  if (!(youngs_modulus > 0.0) || !std::isfinite(youngs_modulus))
    throw std::invalid_argument("linear: Young's modulus must be positive, got " +
                                std::to_string(youngs_modulus));
  if (!(poisson_ratio > -1.0 && poisson_ratio < 0.5))
    throw std::invalid_argument("linear: Poisson's ratio must lie in (-1, 0.5), got " +
                                std::to_string(poisson_ratio));
  const double mu = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
  const double K = youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio));
  return LinearElastic(mu, K);
}

Mat9 LinearElastic::isotropic_tangent(double mu, double lambda) {
  Mat9 A = Mat9::Zero();
  for (int L = 0; L < 3; ++L)
    for (int k = 0; k < 3; ++k)
      for (int J = 0; J < 3; ++J)
        for (int i = 0; i < 3; ++i) {
          const double d_iJ = i == J, d_kL = k == L, d_ik = i == k, d_JL = J == L;
          const double d_iL = i == L, d_kJ = k == J;
          A(flat_index(i, J), flat_index(k, L)) =
              lambda * d_iJ * d_kL + mu * (d_ik * d_JL + d_iL * d_kJ);
        }
  return A;
}

PointResponse LinearElastic::response(const Mat3& F, bool with_tangent) const {
  const Mat3 H = F - Mat3::Identity();
  const Mat3 eps = 0.5 * (H + H.transpose());
  const double tr = eps.trace();
  const double lambda = lame_lambda();
  PointResponse r;
  r.energy = 0.5 * lambda * tr * tr + mu_ * eps.squaredNorm();
  // dW/dF = dW/deps since eps is the symmetric part of F - I and dW/deps is symmetric.
  r.stress = lambda * tr * Mat3::Identity() + 2.0 * mu_ * eps;
  if (with_tangent) r.tangent = tangent_;
  return r;
}

}  // namespace tongue::fem
