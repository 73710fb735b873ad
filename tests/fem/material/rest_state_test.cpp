// Rest state and small-strain limit: P(I) = 0, W(I) = 0, and A(I) equals the isotropic linear
// tangent lambda d_iJ d_kL + mu (d_ik d_JL + d_iL d_kJ) with mu = mu0 and lambda = K - 2 mu0 / 3,
// so that every law agrees with linear elasticity for small strains. At F = I the kernel's terms
// are exact small multiples of the moduli, so 1e-9 relative leaves a wide margin.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "material_test_support.hpp"

namespace tongue::fem::testing {
namespace {

constexpr double kTol = 1e-9;

class RestState : public ::testing::TestWithParam<Case> {};

TEST_P(RestState, StressFreeAndLinearTangent) {
  const auto m = make(GetParam());
  const double mu = m->initial_shear_modulus(), K = m->bulk_modulus();
  const PointResponse r = m->response(Mat3::Identity());
  EXPECT_NEAR(r.energy, 0.0, 1e-14 * mu);
  EXPECT_LE(r.stress.norm(), 1e-14 * mu) << r.stress;
  const Mat9 expected = LinearElastic::isotropic_tangent(mu, K - 2.0 * mu / 3.0);
  const double err = relative(r.tangent, expected);
  EXPECT_LE(err, kTol) << r.tangent;
  std::printf("  [%s] |P(I)| / mu0 %.1e, A(I) vs linear %.1e\n", case_name(GetParam()).c_str(),
              r.stress.norm() / mu, err);

  // The isochoric part alone is the deviatoric tangent (lambda = -2 mu / 3, no bulk stiffness):
  // checked separately because K dominates the full tangent at nu = 0.4999.
  if (const UncoupledMaterial* u = m->as_uncoupled()) {
    const PointResponse iso = u->isochoric_response(Mat3::Identity());
    EXPECT_LE(iso.stress.norm(), 1e-14 * mu);
    const double err_iso =
        relative(iso.tangent, LinearElastic::isotropic_tangent(mu, -2.0 * mu / 3.0));
    EXPECT_LE(err_iso, kTol);
    std::printf("  [%s] isochoric A(I) vs deviatoric linear %.1e\n", case_name(GetParam()).c_str(),
                err_iso);
  }
}

INSTANTIATE_TEST_SUITE_P(AllMaterials, RestState, ::testing::ValuesIn(cases(false)),
                         [](const auto& info) { return case_name(info.param); });

// det F <= 0 is outside the domain: infinite energy and NaN derivatives, never a finite answer.
TEST(RestState, InvertedElementIsRejected) {
  const auto m = make({"mooney_rivlin5", 0.49});
  const Mat3 F = Vec3(1.0, 1.0, -1.0).asDiagonal();
  const PointResponse r = m->response(F);
  EXPECT_TRUE(std::isinf(r.energy));
  EXPECT_TRUE(r.stress.hasNaN());
  EXPECT_TRUE(r.tangent.hasNaN());
}

}  // namespace
}  // namespace tongue::fem::testing
