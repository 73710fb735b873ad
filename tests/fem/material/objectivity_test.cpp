// Objectivity of the hyperelastic laws: W(QF) = W(F), P(QF) = Q P(F) and
// A(QF)_iJkL = Q_ia Q_kb A(F)_aJbL for a rotation Q (Holzapfel 2000, sec. 6.1). On the flattening
// i + 3 J the left action of Q is the block diagonal B = diag(Q, Q, Q): A(QF) = B A(F) B^T.
// The small-strain law is not objective and is excluded.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "material_test_support.hpp"

namespace tongue::fem::testing {
namespace {

// Round-off of O(1)-conditioned products: 1e-12 relative.
constexpr double kTol = 1e-12;

class Objectivity : public ::testing::TestWithParam<Case> {};

TEST_P(Objectivity, RotationLeavesResponseInvariant) {
  const auto m = make(GetParam());
  const Mat3 Q = rotation();
  Mat9 B = Mat9::Zero();
  for (int J = 0; J < 3; ++J) B.block<3, 3>(3 * J, 3 * J) = Q;
  double worst = 0.0;
  for (const Mat3& F : {general_F(), compressive_F()}) {
    const PointResponse r = m->response(F);
    const PointResponse rq = m->response(Q * F);
    const double ew = std::abs(rq.energy - r.energy) / std::abs(r.energy);
    const double ep = relative(rq.stress, Mat3(Q * r.stress));
    const double ea = relative(rq.tangent, Mat9(B * r.tangent * B.transpose()));
    EXPECT_LE(ew, kTol);
    EXPECT_LE(ep, kTol);
    EXPECT_LE(ea, kTol);
    worst = std::max({worst, ew, ep, ea});
  }
  std::printf("  [%s] objectivity: max relative error %.1e\n", case_name(GetParam()).c_str(),
              worst);
}

INSTANTIATE_TEST_SUITE_P(Uncoupled, Objectivity, ::testing::ValuesIn(cases(true)),
                         [](const auto& info) { return case_name(info.param); });

}  // namespace
}  // namespace tongue::fem::testing
