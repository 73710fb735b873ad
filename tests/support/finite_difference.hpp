#pragma once
// Central finite differences for the tangent checks (truncation O(h^2), round-off O(eps / h)).
#include <Eigen/Core>
#include <functional>

namespace tongue::testing {

// Jacobian of f: R^n -> R^m by central differences with step h.
inline Eigen::MatrixXd central_difference_jacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
    double h) {
  const Eigen::VectorXd f0 = f(x);
  Eigen::MatrixXd J(f0.size(), x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    J.col(j) = (f(xp) - f(xm)) / (2.0 * h);
  }
  return J;
}

}  // namespace tongue::testing
