#include "fem/material/ellipticity.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>

namespace tongue::fem {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

constexpr int kDirections = 128;         // even spread over the half sphere
constexpr int kStarts = 3;               // the lattice's weakest local minima refined
constexpr int kRefinements = 50;         // refinement rounds, at most
constexpr double kRelativeGain = 1e-13;  // of |Q|: a round gaining less ends the refinement
constexpr double kPi = 3.14159265358979323846;

// The six products N_J N_L (J <= L) in the order of AcousticMap's columns.
Vec6 products(const Vec3& N) {
  Vec6 p;
  p << N(0) * N(0), N(1) * N(1), N(2) * N(2), N(0) * N(1), N(0) * N(2), N(1) * N(2);
  return p;
}

constexpr int kPairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};

// Q(N) from its six entries on and below the diagonal, a linear map of N's six products:
// Q_ik = sum_JL A_iJkL N_J N_L with the J != L terms paired, 36 multiply-adds a direction
// instead of 81 (the tangent's major symmetry A_iJkL = A_kLiJ makes Q symmetric).
class AcousticMap {
 public:
  explicit AcousticMap(const Mat9& A) {
    for (int r = 0; r < 6; ++r) {
      const int i = kPairs[r][1], k = kPairs[r][0];  // i >= k: the lower triangle
      for (int c = 0; c < 6; ++c) {
        const int J = kPairs[c][0], L = kPairs[c][1];
        G_(r, c) = A(flat_index(i, J), flat_index(k, L));
        if (J != L) G_(r, c) += A(flat_index(i, L), flat_index(k, J));
      }
    }
  }
  Mat3 operator()(const Vec3& N) const {
    const Vec6 q = G_ * products(N);
    Mat3 Q;
    for (int r = 0; r < 6; ++r)
      Q(kPairs[r][1], kPairs[r][0]) = Q(kPairs[r][0], kPairs[r][1]) = q(r);
    return Q;
  }

 private:
  Eigen::Matrix<double, 6, 6> G_;
};

// The search's measure of a direction: Q(N)'s smallest eigenvalue by the closed form for 3 x 3
// symmetric matrices (Smith 1961, Eigen's computeDirect), cheaper than the iterative solver with
// eigenvectors. It differs from the iterative solver's by less than 1e-8 of |Q| (20 000 random
// tangents of mooney_rivlin5, the state at rest among them, where two eigenvalues meet), which
// only steers the search: the weakest direction's eigenpair is computed iteratively at the end.
double smallest_eigenvalue(const Mat3& Q) {
  Eigen::SelfAdjointEigenSolver<Mat3> eig;
  eig.computeDirect(Q, Eigen::EigenvaluesOnly);
  return eig.eigenvalues()(0);
}

// The unit eigenvector of a symmetric 3 x 3 matrix's smallest eigenvalue.
Vec3 weakest_vector(const Mat3& S) {
  Eigen::SelfAdjointEigenSolver<Mat3> eig;
  eig.computeDirect(S, Eigen::ComputeEigenvectors);
  return eig.eigenvectors().col(0).normalized();
}

// B(a)_JL = a_i A_iJkL a_k: for a fixed amplitude a, a . Q(N) a = N . B(a) N.
Mat3 amplitude_tensor(const Mat9& A, const Vec3& a) {
  Mat3 B;
  for (const auto& [J, L] : kPairs) {
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) sum += a(i) * a(k) * A(flat_index(i, J), flat_index(k, L));
    }
    B(L, J) = B(J, L) = sum;
  }
  return B;
}

// Two unit vectors spanning the plane normal to unit v.
Eigen::Matrix<double, 3, 2> tangent_basis(const Vec3& v) {
  const Vec3 helper = std::abs(v(0)) < 0.8 ? Vec3::UnitX() : Vec3::UnitY();
  Eigen::Matrix<double, 3, 2> T;
  T.col(0) = v.cross(helper).normalized();
  T.col(1) = v.cross(T.col(0));
  return T;
}

// One Newton step for a stationary point of g(a, N) = A_iJkL a_i N_J a_k N_L on the product of
// the two unit spheres (Riemannian Newton: the gradient and Hessian projected on the spheres'
// tangent planes, the Hessian corrected by the curvature term -2 g I on each sphere; Absil,
// Mahony & Sepulchre 2008, "Optimization Algorithms on Matrix Manifolds", secs. 5.5 and 6.2).
// Returns false where the projected Hessian is not positive definite (not yet near a minimum).
bool newton_step(const Mat9& A, const AcousticMap& acoustic, Vec3& a, Vec3& N) {
  const Mat3 Q = acoustic(N), B = amplitude_tensor(A, a);
  const double g = a.dot(Q * a);
  Mat3 C = Mat3::Zero();  // the mixed second derivative / 2: C_iM = d(Q(N) a)_i / dN_M
  for (int i = 0; i < 3; ++i) {
    for (int M = 0; M < 3; ++M) {
      for (int k = 0; k < 3; ++k) {
        for (int L = 0; L < 3; ++L) {
          C(i, M) +=
              (A(flat_index(i, M), flat_index(k, L)) + A(flat_index(i, L), flat_index(k, M))) *
              N(L) * a(k);
        }
      }
    }
  }
  const Eigen::Matrix<double, 3, 2> Ta = tangent_basis(a), TN = tangent_basis(N);
  Eigen::Matrix4d H;
  H.topLeftCorner<2, 2>() = Ta.transpose() * (Q - g * Mat3::Identity()) * Ta;
  H.bottomRightCorner<2, 2>() = TN.transpose() * (B - g * Mat3::Identity()) * TN;
  H.topRightCorner<2, 2>() = Ta.transpose() * C * TN;
  H.bottomLeftCorner<2, 2>() = H.topRightCorner<2, 2>().transpose();
  Eigen::Vector4d gradient;
  gradient << Ta.transpose() * (Q * a), TN.transpose() * (B * N);
  const Eigen::LLT<Eigen::Matrix4d> llt(H);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Vector4d d = -llt.solve(gradient);
  a = (a + Ta * d.head<2>()).normalized();
  N = (N + TN * d.tail<2>()).normalized();
  return true;
}

// A Fibonacci lattice on the upper half sphere: nearly uniform, deterministic; its unit
// vectors and each point's nearest neighbours (N and -N being one direction, across the rim
// too), made once.
struct Lattice {
  static constexpr int kNeighbours = 6;
  std::array<Vec3, kDirections> direction;
  std::array<std::array<int, kNeighbours>, kDirections> neighbours;
  Lattice() {
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (int n = 0; n < kDirections; ++n) {
      const double z = 1.0 - (n + 0.5) / kDirections;  // in (0, 1]
      const double r = std::sqrt(1.0 - z * z), azimuth = golden * n;
      direction[n] = Vec3(r * std::cos(azimuth), r * std::sin(azimuth), z);
    }
    for (int n = 0; n < kDirections; ++n) {
      std::array<std::pair<double, int>, kDirections - 1> others;
      for (int m = 0, o = 0; m < kDirections; ++m) {
        if (m != n) others[o++] = {-std::abs(direction[n].dot(direction[m])), m};
      }
      std::partial_sort(others.begin(), others.begin() + kNeighbours, others.end());
      for (int k = 0; k < kNeighbours; ++k) neighbours[n][k] = others[k].second;
    }
  }
};

// Refinement of a . Q(N) a = A_iJkL a_i N_J a_k N_L over the two unit vectors from direction N,
// a round from N and its weakest amplitude a (Q(N)'s eigenvector): a Newton step (newton_step)
// where the Hessian allows and it descends, else half an alternating round, the weakest N for
// that a (B(a)'s eigenvector), which cannot ascend (block coordinate descent) but crawls along
// curved valleys. A direction is measured by Q(N)'s smallest eigenvalue, so the value only ever
// falls, to the minimum of N's basin; returns it.
double refine(const Mat9& A, const AcousticMap& acoustic, Vec3& N) {
  const double scale = A.cwiseAbs().maxCoeff();
  double value = smallest_eigenvalue(acoustic(N));
  for (int round = 0; round < kRefinements; ++round) {
    const Vec3 a = weakest_vector(acoustic(N));
    Vec3 a_next = a, N_next = N;
    double next = value;
    if (newton_step(A, acoustic, a_next, N_next)) next = smallest_eigenvalue(acoustic(N_next));
    if (!(next < value)) {
      N_next = weakest_vector(amplitude_tensor(A, a));
      next = smallest_eigenvalue(acoustic(N_next));
    }
    if (!(next < value)) break;  // no descent left but round-off
    const double gain = value - next;
    value = next;
    N = N_next;
    if (gain <= kRelativeGain * scale) break;
  }
  return value;
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
  static const Lattice lattice;
  const AcousticMap acoustic(A);
  std::array<double, kDirections> values;
  for (int n = 0; n < kDirections; ++n) {
    values[n] = smallest_eigenvalue(acoustic(lattice.direction[n]));
  }
  // The lattice's local minima (no neighbour weaker), the weakest kStarts of them refined: the
  // weakest point alone can sit in a shallower basin than a neighbouring minimum's.
  std::array<std::pair<double, int>, kDirections> minima;
  int count = 0;
  for (int n = 0; n < kDirections; ++n) {
    bool lowest = true;
    for (const int m : lattice.neighbours[n]) lowest = lowest && !(values[m] < values[n]);
    if (lowest) minima[count++] = {values[n], n};
  }
  const int starts = std::min(count, kStarts);
  std::partial_sort(minima.begin(), minima.begin() + starts, minima.begin() + count);
  double best = 0.0;
  Vec3 N = lattice.direction[0];
  for (int s = 0; s < starts; ++s) {
    Vec3 candidate = lattice.direction[minima[s].second];
    const double value = refine(A, acoustic, candidate);
    if (s == 0 || value < best) {
      best = value;
      N = candidate;
    }
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(acoustic(N));
  EllipticityCheck c;
  c.min_eigenvalue = eig.eigenvalues()(0);
  c.direction = N;
  c.amplitude = eig.eigenvectors().col(0);
  return c;
}

}  // namespace tongue::fem
