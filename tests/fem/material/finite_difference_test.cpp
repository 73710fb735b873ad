// P against central differences of W, and A against central differences of P, at strongly
// deformed general F: for the full response of every material, and for the isochoric and
// volumetric parts of the uncoupled kernel separately (the volumetric part dominates at
// nu = 0.4999 and would hide an isochoric error in the full response).
//
// Step h = 1e-6 on F entries of order 1. Central differences have truncation error
// h^2/6 |f'''| ~ 1e-13 relative, and round-off eps |f| / h ~ 2e-16 / 1e-6 ~ 2e-10 relative (|W|
// and |P|, |P| and |A| are of comparable size at these F). Both are far below the 1e-6 bound;
// h near the optimum eps^{1/3} ~ 6e-6 would only trade one for the other. A wrong term in P or
// A is an O(1) relative error, so 1e-6 still catches it.
#include <algorithm>
#include <cstdio>
#include <functional>

#include <gtest/gtest.h>

#include "material_test_support.hpp"

namespace tongue::fem::testing {
namespace {

constexpr double kH = 1e-6;
constexpr double kTol = 1e-6;

using Evaluate = std::function<PointResponse(const Mat3&)>;

Mat3 fd_stress(const Evaluate& f, const Mat3& F) {
  Mat3 P;
  for (int J = 0; J < 3; ++J)
    for (int i = 0; i < 3; ++i) {
      Mat3 Fp = F, Fm = F;
      Fp(i, J) += kH;
      Fm(i, J) -= kH;
      P(i, J) = (f(Fp).energy - f(Fm).energy) / (2.0 * kH);
    }
  return P;
}

Mat9 fd_tangent(const Evaluate& f, const Mat3& F) {
  Mat9 A;
  for (int L = 0; L < 3; ++L)
    for (int k = 0; k < 3; ++k) {
      Mat3 Fp = F, Fm = F;
      Fp(k, L) += kH;
      Fm(k, L) -= kH;
      A.col(flat_index(k, L)) = flatten((f(Fp).stress - f(Fm).stress) / (2.0 * kH));
    }
  return A;
}

struct Errors {
  double stress = 0.0, tangent = 0.0, asymmetry = 0.0;
};

Errors check(const Evaluate& f, const std::string& what) {
  Errors e;
  for (const Mat3& F : {general_F(), compressive_F()}) {
    const PointResponse r = f(F);
    const double es = relative(r.stress, fd_stress(f, F));
    const double et = relative(r.tangent, fd_tangent(f, F));
    const double ea = (r.tangent - r.tangent.transpose()).norm() / r.tangent.norm();
    EXPECT_LE(es, kTol) << what << ": P vs FD of W at F =\n" << F;
    EXPECT_LE(et, kTol) << what << ": A vs FD of P at F =\n" << F;
    EXPECT_LE(ea, 1e-13) << what << ": A not symmetric at F =\n" << F;
    e.stress = std::max(e.stress, es);
    e.tangent = std::max(e.tangent, et);
    e.asymmetry = std::max(e.asymmetry, ea);
  }
  std::printf("  %-34s P %.1e  A %.1e  asym %.1e\n", what.c_str(), e.stress, e.tangent,
              e.asymmetry);
  return e;
}

class FiniteDifference : public ::testing::TestWithParam<Case> {};

TEST_P(FiniteDifference, FullResponse) {
  const auto m = make(GetParam());
  check([&](const Mat3& F) { return m->response(F); }, case_name(GetParam()) + " full");
}

INSTANTIATE_TEST_SUITE_P(AllMaterials, FiniteDifference, ::testing::ValuesIn(cases(false)),
                         [](const auto& info) { return case_name(info.param); });

class FiniteDifferenceParts : public ::testing::TestWithParam<Case> {};

TEST_P(FiniteDifferenceParts, IsochoricPart) {
  const auto m = make(GetParam());
  const UncoupledMaterial* u = m->as_uncoupled();
  ASSERT_NE(u, nullptr);
  check([&](const Mat3& F) { return u->isochoric_response(F); }, case_name(GetParam()) + " iso");
}

// The volumetric part as the kernel assembles it (full minus isochoric), against U(det F).
TEST_P(FiniteDifferenceParts, VolumetricPart) {
  const auto m = make(GetParam());
  const UncoupledMaterial* u = m->as_uncoupled();
  ASSERT_NE(u, nullptr);
  check(
      [&](const Mat3& F) {
        PointResponse r = u->response(F);
        const PointResponse iso = u->isochoric_response(F);
        r.energy = u->volumetric(F.determinant()).energy;
        r.stress -= iso.stress;
        r.tangent -= iso.tangent;
        return r;
      },
      case_name(GetParam()) + " vol");

  // And U(J) itself: U' and U'' against central differences.
  for (double J : {0.8, 1.0, 1.3}) {
    const auto v = u->volumetric(J);
    const double d1 = (u->volumetric(J + kH).energy - u->volumetric(J - kH).energy) / (2 * kH);
    const double d2 = (u->volumetric(J + kH).first - u->volumetric(J - kH).first) / (2 * kH);
    EXPECT_NEAR(v.first, d1, kTol * u->bulk_modulus());
    EXPECT_NEAR(v.second, d2, kTol * u->bulk_modulus());
  }
}

INSTANTIATE_TEST_SUITE_P(Uncoupled, FiniteDifferenceParts, ::testing::ValuesIn(cases(true)),
                         [](const auto& info) { return case_name(info.param); });

}  // namespace
}  // namespace tongue::fem::testing
