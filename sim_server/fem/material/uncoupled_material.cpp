// The shared kernel of every uncoupled material: from the invariant derivatives of W_iso(I1b, I2b)
// to P = dW/dF and A = d2W/dF dF, exactly, on the column-major flattening of types.hpp.
//
// Route (Holzapfel 2000, sec. 6.4 decoupled form, written in F instead of C so that the element
// needs no push-forward): for f = J^{-p} g(F), with T = F^{-T},
//   df/dF  = J^{-p} (dg - p g T)
//   d2f    = J^{-p} [d2g - p (dg (x) T + T (x) dg) + p^2 g T (x) T - p g dT/dF],
//   dT_iJ/dF_kL = -T_iL T_kJ  (derivative of the inverse tensor, Holzapfel 2000, ch. 1).
// I1b = J^{-2/3} I1 (p = 2/3) and I2b = J^{-4/3} I2 (p = 4/3), with
//   I1 = F:F,                   dI1 = 2 F,             d2I1 = 2 d_ik d_JL,
//   I2 = (I1^2 - C:C)/2,        dI2 = 2 (I1 F - F C),
//   d2I2 = 4 F_iJ F_kL + 2 I1 d_ik d_JL - 2 (d_ik C_JL + F_iL F_kJ + b_ik d_JL),  b = F F^T,
//   dJ = J T,                   d2J = J (T_iJ T_kL - T_iL T_kJ).
// Then A_iso = W11 dI1b (x) dI1b + W12 (dI1b (x) dI2b + dI2b (x) dI1b) + W22 dI2b (x) dI2b
//            + W1 d2I1b + W2 d2I2b, and A_vol = U'' dJ (x) dJ + U' d2J.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/LU>  // determinant, inverse

#include "fem/material/material.hpp"

namespace tongue::fem {
namespace {

// Everything about F that both parts need, computed once per call.
struct Kinematics {
  explicit Kinematics(const Mat3& F_in) : F(F_in) {
    J = F.determinant();
    T = F.inverse().transpose();
    C = F.transpose() * F;
    b = F * F.transpose();
    I1 = F.squaredNorm();
    I2 = 0.5 * (I1 * I1 - C.squaredNorm());  // tr(C^2) = C:C since C is symmetric
  }
  Mat3 F, T, C, b;
  double J, I1, I2;
};

// A_{iJkL} += c X_ik Y_JL.
void add_box(Mat9& A, double c, const Mat3& X, const Mat3& Y) {
  for (int L = 0; L < 3; ++L)
    for (int k = 0; k < 3; ++k)
      for (int J = 0; J < 3; ++J)
        for (int i = 0; i < 3; ++i) A(flat_index(i, J), flat_index(k, L)) += c * X(i, k) * Y(J, L);
}

// A_{iJkL} += c X_iL X_kJ.
void add_cross(Mat9& A, double c, const Mat3& X) {
  for (int L = 0; L < 3; ++L)
    for (int k = 0; k < 3; ++k)
      for (int J = 0; J < 3; ++J)
        for (int i = 0; i < 3; ++i) A(flat_index(i, J), flat_index(k, L)) += c * X(i, L) * X(k, J);
}

// A += c (u v^T + v u^T): keeps A exactly symmetric.
void add_sym_outer(Mat9& A, double c, const Vec9& u, const Vec9& v) {
  A.noalias() += (c * u) * v.transpose();
  A.noalias() += (c * v) * u.transpose();
}

void add_isochoric(const UncoupledMaterial& material, const Kinematics& k, bool with_tangent,
                   PointResponse& out) {
  const Mat3 I = Mat3::Identity();
  const double cbrt_J = std::cbrt(k.J);
  const double a1 = 1.0 / (cbrt_J * cbrt_J);  // J^{-2/3}
  const double a2 = a1 * a1;                  // J^{-4/3}
  const InvariantDerivatives w = material.isochoric_derivatives(a1 * k.I1, a2 * k.I2);
  // Neo-Hookean and exponential laws do not depend on I2b: skip half of the work for them.
  const bool uses_I2 = w.d2 != 0.0 || w.d12 != 0.0 || w.d22 != 0.0;

  const Vec9 t = flatten(k.T);
  const Mat3 dI1 = 2.0 * k.F;
  const Mat3 dI1b = a1 * (dI1 - (2.0 / 3.0) * k.I1 * k.T);
  const Vec9 u1 = flatten(dI1b);

  out.energy += w.energy;
  out.stress += w.d1 * dI1b;
  const Mat3 dI2 = 2.0 * (k.I1 * k.F - k.F * k.C);
  const Mat3 dI2b = a2 * (dI2 - (4.0 / 3.0) * k.I2 * k.T);
  if (uses_I2) out.stress += w.d2 * dI2b;
  if (!with_tangent) return;

  Mat9& A = out.tangent;
  A.noalias() += (w.d11 * u1) * u1.transpose();

  // W1 d2I1b, with g = I1, p = 2/3.
  const double s1 = w.d1 * a1;
  A.diagonal().array() += 2.0 * s1;  // d2I1 = 2 d_ik d_JL is twice the 9x9 identity
  add_sym_outer(A, -(2.0 / 3.0) * s1, flatten(dI1), t);
  A.noalias() += ((4.0 / 9.0) * s1 * k.I1 * t) * t.transpose();
  add_cross(A, (2.0 / 3.0) * s1 * k.I1, k.T);

  if (!uses_I2) return;

  const Vec9 u2 = flatten(dI2b);
  add_sym_outer(A, w.d12, u1, u2);
  A.noalias() += (w.d22 * u2) * u2.transpose();

  // W2 d2I2b, with g = I2, p = 4/3.
  const double s2 = w.d2 * a2;
  const Vec9 f = flatten(k.F);
  A.noalias() += (4.0 * s2 * f) * f.transpose();
  A.diagonal().array() += 2.0 * s2 * k.I1;
  add_box(A, -2.0 * s2, I, k.C);
  add_box(A, -2.0 * s2, k.b, I);
  add_cross(A, -2.0 * s2, k.F);
  add_sym_outer(A, -(4.0 / 3.0) * s2, flatten(dI2), t);
  A.noalias() += ((16.0 / 9.0) * s2 * k.I2 * t) * t.transpose();
  add_cross(A, (4.0 / 3.0) * s2 * k.I2, k.T);
}

void add_volumetric(const VolumetricResponse& u, const Kinematics& k, bool with_tangent,
                    PointResponse& out) {
  out.energy += u.energy;
  out.stress += (u.first * k.J) * k.T;
  if (!with_tangent) return;
  const Vec9 t = flatten(k.T);
  // U'' (J T) (x) (J T) + U' J (T (x) T - T_iL T_kJ).
  out.tangent.noalias() += ((u.second * k.J * k.J + u.first * k.J) * t) * t.transpose();
  add_cross(out.tangent, -u.first * k.J, k.T);
}

PointResponse zero_response(bool with_tangent) {
  PointResponse r;
  r.energy = 0.0;
  r.stress.setZero();
  if (with_tangent) r.tangent.setZero();
  return r;
}

// det F <= 0 violates the precondition. Rather than throw at a Gauss point (possibly inside a
// parallel loop), return an infinite energy and NaN derivatives, which any Newton residual or
// line-search test rejects.
PointResponse inverted_response() {
  PointResponse r;
  r.energy = std::numeric_limits<double>::infinity();
  r.stress.setConstant(std::numeric_limits<double>::quiet_NaN());
  r.tangent.setConstant(std::numeric_limits<double>::quiet_NaN());
  return r;
}

}  // namespace

UncoupledMaterial::UncoupledMaterial(double bulk_modulus) : bulk_modulus_(bulk_modulus) {
  if (!(bulk_modulus > 0.0) || !std::isfinite(bulk_modulus))
    throw std::invalid_argument("bulk modulus must be positive and finite, got " +
                                std::to_string(bulk_modulus));
}

VolumetricResponse UncoupledMaterial::volumetric(double J) const {
  // U = K/2 (J - 1)^2: the simplest convex penalty, as in FEBio's default "uncoupled" option.
  VolumetricResponse u;
  u.energy = 0.5 * bulk_modulus_ * (J - 1.0) * (J - 1.0);
  u.first = bulk_modulus_ * (J - 1.0);
  u.second = bulk_modulus_;
  return u;
}

void UncoupledMaterial::isochoric_first_derivatives(int n, const double* I1_bar,
                                                    const double* I2_bar, double* energy,
                                                    double* d1, double* d2) const {
  for (int p = 0; p < n; ++p) {
    const InvariantDerivatives w = isochoric_derivatives(I1_bar[p], I2_bar[p]);
    energy[p] = w.energy;
    d1[p] = w.d1;
    d2[p] = w.d2;
  }
}

void UncoupledMaterial::isochoric_second_derivatives(int n, const double* I1_bar,
                                                     const double* I2_bar, double* energy,
                                                     double* d1, double* d2, double* d11,
                                                     double* d12, double* d22) const {
  for (int p = 0; p < n; ++p) {
    const InvariantDerivatives w = isochoric_derivatives(I1_bar[p], I2_bar[p]);
    energy[p] = w.energy;
    d1[p] = w.d1;
    d2[p] = w.d2;
    d11[p] = w.d11;
    d12[p] = w.d12;
    d22[p] = w.d22;
  }
}

PointResponse UncoupledMaterial::isochoric_response(const Mat3& F, bool with_tangent) const {
  const Kinematics k(F);
  if (!(k.J > 0.0)) return inverted_response();
  PointResponse r = zero_response(with_tangent);
  add_isochoric(*this, k, with_tangent, r);
  return r;
}

PointResponse UncoupledMaterial::response(const Mat3& F, bool with_tangent) const {
  const Kinematics k(F);
  if (!(k.J > 0.0)) return inverted_response();
  PointResponse r = zero_response(with_tangent);
  add_isochoric(*this, k, with_tangent, r);
  add_volumetric(volumetric(k.J), k, with_tangent, r);
  return r;
}

double bulk_modulus_from_poisson(double shear_modulus, double poisson_ratio) {
  if (!(shear_modulus > 0.0) || !std::isfinite(shear_modulus))
    throw std::invalid_argument("shear modulus must be positive and finite, got " +
                                std::to_string(shear_modulus));
  if (!(poisson_ratio > -1.0 && poisson_ratio < 0.5))
    throw std::invalid_argument("Poisson's ratio must lie in (-1, 0.5), got " +
                                std::to_string(poisson_ratio));
  // Isotropic linear elasticity: K = E / (3 (1 - 2 nu)) with E = 2 mu (1 + nu).
  return 2.0 * shear_modulus * (1.0 + poisson_ratio) / (3.0 * (1.0 - 2.0 * poisson_ratio));
}

}  // namespace tongue::fem
