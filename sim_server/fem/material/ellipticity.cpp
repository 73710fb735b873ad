#include "fem/material/ellipticity.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace tongue::fem {
namespace {

constexpr int kDirections = 128;  // even spread over the half sphere
constexpr int kRefinements = 40;  // local pattern-search halvings around the weakest
constexpr double kPi = 3.14159265358979323846;

Vec3 from_angles(double polar, double azimuth) {
  return {std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
          std::cos(polar)};
}

// Smallest eigenpair of Q(N).
EllipticityCheck weakest_at(const Mat9& A, const Vec3& N) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(acoustic_tensor(A, N));
  EllipticityCheck c;
  c.min_eigenvalue = eig.eigenvalues()(0);
  c.direction = N;
  c.amplitude = eig.eigenvectors().col(0);
  return c;
}

}  // namespace

Mat3 acoustic_tensor(const Mat9& A, const Vec3& N) {
  Mat3 Q = Mat3::Zero();
  for (int J = 0; J < 3; ++J) {
    for (int L = 0; L < 3; ++L) {
      const double w = N(J) * N(L);
      if (w == 0.0) continue;
      for (int k = 0; k < 3; ++k) {
        for (int i = 0; i < 3; ++i) Q(i, k) += w * A(flat_index(i, J), flat_index(k, L));
      }
    }
  }
  return Q;
}

EllipticityCheck check_ellipticity(const Material& material, const Mat3& F) {
  const Mat9 A = material.response(F, true).tangent;
  // Fibonacci lattice on the upper half sphere: nearly uniform, deterministic.
  EllipticityCheck best;
  double best_polar = 0.0, best_azimuth = 0.0;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int n = 0; n < kDirections; ++n) {
    const double z = 1.0 - (n + 0.5) / kDirections;  // (0, 1]
    const double polar = std::acos(z), azimuth = golden * n;
    const EllipticityCheck c = weakest_at(A, from_angles(polar, azimuth));
    if (n == 0 || c.min_eigenvalue < best.min_eigenvalue) {
      best = c;
      best_polar = polar;
      best_azimuth = azimuth;
    }
  }
  // Pattern search in the two angles, step halved whenever no neighbour is weaker.
  double step = std::sqrt(4.0 * kPi / kDirections);
  for (int r = 0; r < kRefinements; ++r) {
    bool moved = false;
    for (const auto& [dp, da] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}}) {
      const double polar = best_polar + dp * step, azimuth = best_azimuth + da * step;
      const EllipticityCheck c = weakest_at(A, from_angles(polar, azimuth));
      if (c.min_eigenvalue < best.min_eigenvalue) {
        best = c;
        best_polar = polar;
        best_azimuth = azimuth;
        moved = true;
      }
    }
    if (!moved) step *= 0.5;
  }
  return best;
}

}  // namespace tongue::fem
