// Cauchy stress of the kernel (sigma = P F^T / J) against closed-form homogeneous solutions.
//
// Tolerance: relative 1e-8 on sigma, the lead's requirement. Expected round-off is far below it:
// the stresses are sums of O(1)-conditioned terms times moduli, except the pressure U'(J) =
// K (J - 1), where J - 1 ~ sigma / K carries the rounding of det F, an absolute error of about
// K * 1e-16 in sigma, i.e. a relative error of (K / mu) * 1e-16 <= 5000 * 1e-16 ~ 1e-12 at
// nu = 0.4999. The 1e-8 bound therefore leaves 3-4 orders of margin while still catching any
// wrong term (those are O(1) relative).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "material_test_support.hpp"

namespace tongue::fem::testing {
namespace {

constexpr double kTol = 1e-8;

class ClosedForm : public ::testing::TestWithParam<Case> {};

// Simple shear F = I + gamma e1 (x) e2, J = 1. With b = F F^T and W1, W2 at I1b = I2b = 3 + g^2,
// sigma = 2 dev[(W1 + I1b W2) b - W2 b^2] + U'(1) I (Holzapfel 2000, sec. 6.4) reduces to
//   sigma12 = 2 g (W1 + W2),  sigma11 - sigma22 = 2 g^2 (W1 + W2),  sigma22 - sigma33 = -2 g^2 W2,
//   tr sigma = 3 U'(1) = 0, sigma13 = sigma23 = 0.
// (neo-Hookean: sigma12 = mu g, sigma11 - sigma22 = mu g^2; exponential: 2 g a exp(b g^2).)
// Linear: P = 2 mu eps with eps12 = g/2, so sigma = P F^T = mu [[g^2, g, 0], [g, 0, 0], [0, 0, 0]].
TEST_P(ClosedForm, SimpleShear) {
  const auto m = make(GetParam());
  double worst = 0.0;
  for (double g : {0.05, 0.3, 0.8, 1.5}) {
    Mat3 F = Mat3::Identity();
    F(0, 1) = g;
    Mat3 expected = Mat3::Zero();
    if (m->as_uncoupled()) {
      const auto [W1, W2] = closed_form_derivatives(*m, 3.0 + g * g, 3.0 + g * g);
      const double s12 = 2.0 * g * (W1 + W2);
      const double n1 = 2.0 * g * g * (W1 + W2);
      const double n2 = -2.0 * g * g * W2;
      const double s22 = (n2 - n1) / 3.0;  // from the three relations and tr sigma = 0
      expected(0, 1) = expected(1, 0) = s12;
      expected(0, 0) = s22 + n1;
      expected(1, 1) = s22;
      expected(2, 2) = s22 - n2;
    } else {
      const double mu = m->initial_shear_modulus();
      expected(0, 1) = expected(1, 0) = mu * g;
      expected(0, 0) = mu * g * g;
    }
    const Mat3 sigma = cauchy(m->response(F).stress, F);
    const double err = relative(sigma, expected);
    EXPECT_LE(err, kTol) << "gamma = " << g << "\nsigma =\n" << sigma << "\nexpected\n" << expected;
    worst = std::max(worst, err);
  }
  std::printf("  [%s] simple shear: max relative error %.2e\n", case_name(GetParam()).c_str(),
              worst);
}

// Principal Cauchy stresses of an uncoupled material with principal stretches l_i
// (Holzapfel 2000, sec. 6.4), lb_i = J^{-1/3} l_i:
//   sigma_i = (2/J) [(W1 + I1b W2) lb_i^2 - W2 lb_i^4]
//           - (2/(3J)) [(W1 + I1b W2) I1b - W2 sum_j lb_j^4] + U'(J),   U'(J) = K (J - 1).
Vec3 principal_stress(const Material& m, const Vec3& l) {
  const double J = l.prod();
  const Vec3 lb = std::cbrt(1.0 / J) * l;
  const Vec3 lb2 = lb.cwiseProduct(lb);
  const Vec3 lb4 = lb2.cwiseProduct(lb2);
  const double I1b = lb2.sum();
  const double I2b = 0.5 * (I1b * I1b - lb4.sum());
  const auto [W1, W2] = closed_form_derivatives(m, I1b, I2b);
  const double a = W1 + I1b * W2;
  const double mean = (2.0 / (3.0 * J)) * (a * I1b - W2 * lb4.sum());
  const double pressure_term = m.bulk_modulus() * (J - 1.0);
  return ((2.0 / J) * (a * lb2 - W2 * lb4)).array() - mean + pressure_term;
}

// Linear, uniaxial stress: P22 = 0 gives t = 1 - nu (l - 1) exactly and P11 = E (l - 1), so
// sigma11 = P11 l / J = E (l - 1) / t^2.
TEST_P(ClosedForm, UniaxialStress) {
  const auto m = make(GetParam());
  double worst = 0.0;
  for (double l : {0.6, 0.9, 1.2, 1.6}) {
    double t = 0.0, s11 = 0.0;
    if (m->as_uncoupled()) {
      // Bisection on the lateral stress of the closed form: it rises with t (J and the lateral
      // stretch both grow), so one sign change in [0.2, 3] brackets the root.
      auto lateral = [&](double tt) { return principal_stress(*m, Vec3(l, tt, tt))(1); };
      double lo = 0.2, hi = 3.0;
      ASSERT_LT(lateral(lo), 0.0);
      ASSERT_GT(lateral(hi), 0.0);
      for (int it = 0; it < 200 && hi - lo > 1e-16 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (lateral(mid) < 0.0)
          lo = mid;
        else
          hi = mid;
      }
      t = 0.5 * (lo + hi);
      s11 = principal_stress(*m, Vec3(l, t, t))(0);
    } else {
      const double mu = m->initial_shear_modulus(), K = m->bulk_modulus();
      const double E = 9.0 * K * mu / (3.0 * K + mu);
      const double nu = (3.0 * K - 2.0 * mu) / (2.0 * (3.0 * K + mu));
      t = 1.0 - nu * (l - 1.0);
      s11 = E * (l - 1.0) / (t * t);
    }
    const Mat3 F = Vec3(l, t, t).asDiagonal();
    const Mat3 sigma = cauchy(m->response(F).stress, F);
    Mat3 expected = Mat3::Zero();
    expected(0, 0) = s11;
    // sigma_22, sigma_33 (and the shear components) must vanish on the scale of |sigma_11|.
    const double err = (sigma - expected).norm() / std::abs(s11);
    EXPECT_LE(err, kTol) << "l = " << l << ", t = " << t << "\nsigma =\n" << sigma;
    worst = std::max(worst, err);
  }
  std::printf("  [%s] uniaxial: max relative error %.2e\n", case_name(GetParam()).c_str(), worst);
}

INSTANTIATE_TEST_SUITE_P(AllMaterials, ClosedForm, ::testing::ValuesIn(cases(false)),
                         [](const auto& info) { return case_name(info.param); });

// Cauchy stress of a hyperelastic, objective material is symmetric for any F (balance of angular
// momentum). The small-strain law is not objective, hence excluded.
class Symmetry : public ::testing::TestWithParam<Case> {};

TEST_P(Symmetry, CauchyStressIsSymmetric) {
  const auto m = make(GetParam());
  for (const Mat3& F : {general_F(), compressive_F()}) {
    const Mat3 sigma = cauchy(m->response(F).stress, F);
    EXPECT_LE((sigma - sigma.transpose()).norm() / sigma.norm(), 1e-13) << sigma;
  }
}

INSTANTIATE_TEST_SUITE_P(Uncoupled, Symmetry, ::testing::ValuesIn(cases(true)),
                         [](const auto& info) { return case_name(info.param); });

// The brief's literal closed forms, as a readable anchor for the general formula above.
TEST(ClosedFormLiteral, NeoHookeanAndExponentialSimpleShear) {
  const double g = 0.7, mu = 3000.0, a = 2500.0, b = 0.2526;
  Mat3 F = Mat3::Identity();
  F(0, 1) = g;
  const auto nh = make_material("neo_hookean", {{"shear_modulus", mu}});
  const Mat3 s = cauchy(nh->response(F).stress, F);
  EXPECT_NEAR(s(0, 1), mu * g, 1e-10 * mu);
  EXPECT_NEAR(s(0, 0) - s(1, 1), mu * g * g, 1e-10 * mu);
  EXPECT_NEAR(s(1, 1) - s(2, 2), 0.0, 1e-10 * mu);
  const auto ex = make_material("exponential", {{"a", a}, {"b", b}});
  const Mat3 se = cauchy(ex->response(F).stress, F);
  EXPECT_NEAR(se(0, 1), 2.0 * g * a * std::exp(b * g * g), 1e-10 * a);
}

}  // namespace
}  // namespace tongue::fem::testing
