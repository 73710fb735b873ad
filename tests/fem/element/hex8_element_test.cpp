// The hexahedron's internal force and tangent are the exact derivatives of its energy: checked by
// central finite differences for every material, with and without mean dilatation, at a strongly
// deformed, non-homogeneous state; the fast kernels reproduce the reference element.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>

#include "fem/element/hex8_batch.hpp"
#include "fem/element/hex8_batch_tangent.hpp"
#include "fem/element/hex8_element.hpp"
#include "fem/material/material_factory.hpp"
#include "support/finite_difference.hpp"
#include "support/reference_hex8_element.hpp"

namespace tongue::fem {
namespace {

using testing::central_difference_jacobian;

// A distorted reference element (10 mm), so that dN/dX varies over the element.
hex8::ElementCoords reference_element() {
  hex8::ElementCoords X;
  for (int a = 0; a < 8; ++a) {
    X.row(a) << hex8::kNodeCoords[a][0], hex8::kNodeCoords[a][1], hex8::kNodeCoords[a][2];
  }
  X = 0.005 * (X.array() + 1.0);
  X.row(6) += Eigen::RowVector3d(0.002, 0.001, -0.0015);
  X.row(1) += Eigen::RowVector3d(0.001, -0.0005, 0.0);
  return X;
}

// Large stretch, shear and rotation plus a non-homogeneous part: det F varies over the element.
hex8::ElementCoords deformed(const hex8::ElementCoords& X) {
  Mat3 F;
  F << 1.4, 0.35, 0.1, -0.05, 0.75, 0.2, 0.1, -0.15, 1.05;
  const Mat3 R = Eigen::AngleAxisd(0.6, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  hex8::ElementCoords x = X * (R * F).transpose();
  x.row(2) += Eigen::RowVector3d(0.0008, -0.0006, 0.0004);
  x.row(7) += Eigen::RowVector3d(-0.0005, 0.0007, 0.0009);
  return x;
}

std::shared_ptr<Material> make(const std::string& type, double nu) {
  std::map<std::string, double> p{{"poisson_ratio", nu}};
  if (type == "neo_hookean") p["shear_modulus"] = 3000.0;
  if (type == "linear") p["youngs_modulus"] = 15e3;
  return make_material(type, p);
}

Eigen::VectorXd flatten_coords(const hex8::ElementCoords& x) {
  Eigen::VectorXd v(24);
  for (int a = 0; a < 8; ++a) v.segment<3>(3 * a) = x.row(a).transpose();
  return v;
}
hex8::ElementCoords unflatten(const Eigen::VectorXd& v) {
  hex8::ElementCoords x;
  for (int a = 0; a < 8; ++a) x.row(a) = v.segment<3>(3 * a).transpose();
  return x;
}

struct Case {
  std::string material;
  double nu;
  Formulation formulation;
};

class ElementDerivatives : public ::testing::TestWithParam<Case> {};

TEST_P(ElementDerivatives, ForceAndTangentMatchFiniteDifferences) {
  const Case c = GetParam();
  const auto material = make(c.material, c.nu);
  const hex8::ElementCoords X = reference_element();
  const ElementGeometry geometry = make_element_geometry(X);
  const Eigen::VectorXd x0 = flatten_coords(deformed(X));

  ElementResponse r;
  ASSERT_TRUE(evaluate_element(geometry, unflatten(x0), *material, c.formulation, true, r));
  ASSERT_GT(r.min_J, 0.3);

  auto energy = [&](const Eigen::VectorXd& x) {
    ElementResponse e;
    EXPECT_TRUE(evaluate_element(geometry, unflatten(x), *material, c.formulation, false, e));
    return Eigen::VectorXd::Constant(1, e.energy);
  };
  auto force = [&](const Eigen::VectorXd& x) {
    ElementResponse e;
    EXPECT_TRUE(evaluate_element(geometry, unflatten(x), *material, c.formulation, false, e));
    return Eigen::VectorXd(e.force);
  };
  // h = 1e-8 m on a 10 mm element (relative 1e-6): the O(h^2) truncation error is ~1e-12 of the
  // result and round-off ~ eps / 1e-6 ~ 1e-10, both far below the 1e-6 required.
  const double h = 1e-8;
  const Eigen::MatrixXd dE = central_difference_jacobian(energy, x0, h).transpose();
  const Eigen::MatrixXd dF = central_difference_jacobian(force, x0, h);

  const double force_error = (dE - Eigen::MatrixXd(r.force)).norm() / r.force.norm();
  const double tangent_error = (dF - Eigen::MatrixXd(r.stiffness)).norm() / r.stiffness.norm();
  std::printf("  relative error: force %.1e, tangent %.1e\n", force_error, tangent_error);
  EXPECT_LT(force_error, 1e-6);
  EXPECT_LT(tangent_error, 1e-6);
  EXPECT_LT((r.stiffness - r.stiffness.transpose()).norm() / r.stiffness.norm(), 1e-12);
}

// The residual path (lean stress, pressure folded into the stress, no tangent) and the tangent
// path give what the straightforward evaluation through Material::response gave before them.
TEST_P(ElementDerivatives, FastKernelsReproduceTheStraightforwardEvaluation) {
  const Case c = GetParam();
  const auto material = make(c.material, c.nu);
  const hex8::ElementCoords X = reference_element();
  const ElementGeometry geometry = make_element_geometry(X);
  const hex8::ElementCoords x = deformed(X);

  ElementResponse expected, force_only, with_tangent;
  ASSERT_TRUE(
      testing::reference_evaluate_element(geometry, x, *material, c.formulation, true, expected));
  ASSERT_TRUE(evaluate_element(geometry, x, *material, c.formulation, false, force_only));
  ASSERT_TRUE(evaluate_element(geometry, x, *material, c.formulation, true, with_tangent));
  // The same sums in another order: differences are round-off, ~1e-15 of the magnitudes; 1e-12
  // leaves room for the cancellation in the nearly incompressible cases (K / mu up to 5e3).
  const double tol = 1e-12;
  EXPECT_LT((force_only.force - expected.force).norm(), tol * expected.force.norm());
  EXPECT_NEAR(force_only.energy, expected.energy, tol * std::abs(expected.energy));
  EXPECT_DOUBLE_EQ(force_only.min_J, expected.min_J);
  EXPECT_LT((with_tangent.force - expected.force).norm(), tol * expected.force.norm());
  EXPECT_LT((with_tangent.stiffness - expected.stiffness).norm(), tol * expected.stiffness.norm());
}

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (const std::string m : {"mooney_rivlin5", "exponential", "neo_hookean", "linear"}) {
    for (double nu : {0.3, 0.49, 0.4999}) {
      cases.push_back({m, nu, Formulation::standard});
      if (m != "linear") cases.push_back({m, nu, Formulation::mean_dilatation});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(
    AllMaterials, ElementDerivatives, ::testing::ValuesIn(all_cases()), [](const auto& info) {
      std::string name =
          info.param.material + "_nu" + std::to_string(static_cast<int>(info.param.nu * 1e4)) +
          (info.param.formulation == Formulation::standard ? "_standard" : "_mean_dilatation");
      return name;
    });

// Each kernel of the batch (one per instruction set this CPU runs) gives, lane by lane, the
// reference element's force, energy and smallest det F: 8 different elements mildly deformed
// (det F within [0.5, 2], where the kernel computes J^{-1/3} itself) and 5 strongly deformed and
// dilated ones (det F above 2: std::cbrt) in a partial batch, one of them inverted.
TEST(ElementBatch, EveryKernelTheCpuRunsReproducesTheReferenceElement) {
  for (const std::string type : {"mooney_rivlin5", "neo_hookean"}) {
    const auto material = make(type, 0.49);
    for (Formulation formulation : {Formulation::standard, Formulation::mean_dilatation}) {
      for (const bool strong : {false, true}) {
        const int count = strong ? 5 : 8;
        std::vector<ElementGeometry> geometry;
        std::vector<hex8::ElementCoords> x;
        BatchCoords coords;
        for (int l = 0; l < count; ++l) {
          hex8::ElementCoords X = reference_element();
          X.row(l) += Eigen::RowVector3d(0.3e-3 * l, -0.2e-3, 0.1e-3 * (l % 3));
          geometry.push_back(make_element_geometry(X));
          x.push_back(strong ? hex8::ElementCoords(1.5 * deformed(X))
                             : hex8::ElementCoords(X + (0.2 + 0.05 * l) * (deformed(X) - X)));
        }
        const int inverted = strong ? 3 : -1;
        if (strong) x[inverted].row(6) = x[inverted].row(0) - Eigen::RowVector3d(1e-3, 1e-3, 1e-3);
        for (int l = 0; l < kBatchLanes; ++l)
          for (int k = 0; k < 24; ++k) coords[k].lane[l] = x[l < count ? l : 0](k / 3, k % 3);
        const ElementBatchGeometry batch = make_batch_geometry(geometry);
        for (SimdLevel level : {SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512}) {
          if (level > best_simd_level()) continue;
          SCOPED_TRACE(type + (strong ? " strong, level " : " mild, level ") +
                       std::to_string(static_cast<int>(level)));
          ElementBatchResponse r;
          evaluate_batch_force(batch, coords, *material->as_uncoupled(), formulation, r, level);
          for (int l = 0; l < count; ++l) {
            ElementResponse expected;
            const bool ok = testing::reference_evaluate_element(geometry[l], x[l], *material,
                                                                formulation, false, expected);
            EXPECT_EQ(r.ok[l], ok) << "lane " << l;
            if (!ok) continue;
            EXPECT_GT(expected.min_J, strong ? 2.0 : 0.5);
            ElementVector f;
            for (int k = 0; k < 24; ++k) f[k] = r.force[k].lane[l];
            // The same sums in another order, with or without fused multiply-adds: round-off
            // (measured ~3e-16 of the norm); 1e-13 fails for a J^{-1/3} off by 1e-12.
            EXPECT_LT((f - expected.force).norm(), 1e-13 * expected.force.norm()) << "lane " << l;
            EXPECT_NEAR(r.energy.lane[l], expected.energy, 1e-13 * expected.energy);
            EXPECT_NEAR(r.min_J.lane[l], expected.min_J, 1e-14 * expected.min_J);
          }
          if (strong) {
            EXPECT_FALSE(r.ok[inverted]);
          }
        }
      }
    }
  }
}

// Elements of a test batch: `count` different distorted elements, mildly deformed (det F within
// [0.5, 2]) or strongly deformed and dilated (det F above 2), with one of them inverted if asked.
struct TestBatch {
  std::vector<ElementGeometry> geometry;
  std::vector<hex8::ElementCoords> x;
  BatchCoords coords;
};
TestBatch make_test_batch(int count, bool strong, int inverted = -1) {
  TestBatch t;
  for (int l = 0; l < count; ++l) {
    hex8::ElementCoords X = reference_element();
    X.row(l) += Eigen::RowVector3d(0.3e-3 * l, -0.2e-3, 0.1e-3 * (l % 3));
    X.row(7 - l) += Eigen::RowVector3d(-0.1e-3, 0.2e-3 * (l % 2), 0.15e-3);
    t.geometry.push_back(make_element_geometry(X));
    t.x.push_back(strong ? hex8::ElementCoords(1.5 * deformed(X))
                         : hex8::ElementCoords(X + (0.2 + 0.1 * l) * (deformed(X) - X)));
  }
  if (inverted >= 0)
    t.x[inverted].row(6) = t.x[inverted].row(0) - Eigen::RowVector3d(1e-3, 1e-3, 1e-3);
  for (int l = 0; l < kBatchLanes; ++l)
    for (int k = 0; k < 24; ++k) t.coords[k].lane[l] = t.x[l < count ? l : 0](k / 3, k % 3);
  return t;
}

std::vector<SimdLevel> levels_this_cpu_runs() {
  std::vector<SimdLevel> levels;
  for (SimdLevel level : {SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512})
    if (level <= best_simd_level()) levels.push_back(level);
  return levels;
}

// The tangent kernel (every version this CPU runs) gives, lane by lane, the reference element's
// stiffness, force, energy and smallest det F: every uncoupled law (mooney_rivlin5 with its
// default c20, c11, c02, all nonzero, so that the second invariant derivatives enter; neo_hookean
// and exponential without I2), both formulations, compressible to nearly incompressible; a full
// batch mildly deformed and a partial one (5 elements) strongly deformed, one of them inverted.
TEST(ElementBatchTangent, EveryKernelTheCpuRunsReproducesTheReferenceElement) {
  for (const std::string type : {"mooney_rivlin5", "neo_hookean", "exponential"}) {
    for (const double nu : {0.3, 0.49, 0.4999}) {
      const auto material = make(type, nu);
      for (Formulation formulation : {Formulation::standard, Formulation::mean_dilatation}) {
        for (const bool strong : {false, true}) {
          const int count = strong ? 5 : 8, inverted = strong ? 3 : -1;
          const TestBatch batch = make_test_batch(count, strong, inverted);
          const ElementBatchGeometry geometry = make_batch_geometry(batch.geometry);
          for (SimdLevel level : levels_this_cpu_runs()) {
            SCOPED_TRACE(type + " nu " + std::to_string(nu) +
                         (formulation == Formulation::standard ? " standard" : " mean dilatation") +
                         (strong ? " strong" : " mild") + ", level " +
                         std::to_string(static_cast<int>(level)));
            ElementBatchTangent t;
            evaluate_batch_tangent(geometry, batch.coords, *material->as_uncoupled(), formulation,
                                   t, level);
            for (int l = 0; l < count; ++l) {
              ElementResponse expected, scalar;
              const bool ok = testing::reference_evaluate_element(
                  batch.geometry[l], batch.x[l], *material, formulation, true, expected);
              ASSERT_EQ(t.response.ok[l], ok) << "lane " << l;
              if (!ok) continue;
              ASSERT_TRUE(evaluate_element(batch.geometry[l], batch.x[l], *material, formulation,
                                           true, scalar));
              EXPECT_GT(expected.min_J, strong ? 2.0 : 0.5);
              const ElementMatrix K = lane_stiffness(t, l);
              ElementVector f;
              for (int k = 0; k < 24; ++k) f[k] = t.response.force[k].lane[l];
              // The same terms summed in another order (A grouped by tensor, the volumetric
              // Hessian folded into A), with or without fused multiply-adds: each entry is a sum
              // of ~1e3 products, so its round-off is at worst ~1e3 eps ~ 2e-13 of the largest
              // entry (measured 1.3e-15; the scalar tangent differs from the reference by 4e-16).
              // 1e-12 of the largest entry still fails for any wrong term by orders of magnitude.
              const double scale = expected.stiffness.cwiseAbs().maxCoeff();
              EXPECT_LT((K - expected.stiffness).cwiseAbs().maxCoeff(), 1e-12 * scale)
                  << "lane " << l;
              EXPECT_LT((K - scalar.stiffness).cwiseAbs().maxCoeff(), 1e-12 * scale)
                  << "lane " << l;
              // Force and energy: as the residual kernel's (measured up to 9e-15 of the norm, at
              // nu = 0.4999, where the pressure nearly cancels the deviatoric stress).
              EXPECT_LT((f - expected.force).norm(), 1e-13 * expected.force.norm()) << "lane " << l;
              EXPECT_NEAR(t.response.energy.lane[l], expected.energy, 1e-13 * expected.energy);
              EXPECT_NEAR(t.response.min_J.lane[l], expected.min_J, 1e-14 * expected.min_J);
            }
            if (strong) {
              EXPECT_FALSE(t.response.ok[inverted]);
            }
          }
        }
      }
    }
  }
}

// The kernel's stiffness is the derivative of its own force, and its force that of its energy:
// central differences of the batch, each dof moved in every lane at once (the lanes are
// independent), for 8 different deformed elements.
TEST(ElementBatchTangent, StiffnessAndForceMatchFiniteDifferencesOfTheKernel) {
  for (const std::string type : {"mooney_rivlin5", "exponential"}) {
    const auto material = make(type, 0.49);
    for (Formulation formulation : {Formulation::standard, Formulation::mean_dilatation}) {
      const TestBatch batch = make_test_batch(8, false);
      const ElementBatchGeometry geometry = make_batch_geometry(batch.geometry);
      for (SimdLevel level : levels_this_cpu_runs()) {
        SCOPED_TRACE(type + (formulation == Formulation::standard ? " standard" : " mean") +
                     ", level " + std::to_string(static_cast<int>(level)));
        ElementBatchTangent t, plus, minus;
        const UncoupledMaterial& m = *material->as_uncoupled();
        evaluate_batch_tangent(geometry, batch.coords, m, formulation, t, level);
        // h = 1e-8 m on 10 mm elements (relative 1e-6): truncation O(h^2) ~ 1e-12 and round-off
        // ~ eps / 1e-6 ~ 1e-10 of the result, far below the 1e-6 required.
        const double h = 1e-8;
        std::array<ElementMatrix, kBatchLanes> dF;
        std::array<ElementVector, kBatchLanes> dE;
        for (int j = 0; j < 24; ++j) {
          BatchCoords xp = batch.coords, xm = batch.coords;
          for (int l = 0; l < kBatchLanes; ++l) {
            xp[j].lane[l] += h;
            xm[j].lane[l] -= h;
          }
          evaluate_batch_tangent(geometry, xp, m, formulation, plus, level);
          evaluate_batch_tangent(geometry, xm, m, formulation, minus, level);
          for (int l = 0; l < kBatchLanes; ++l) {
            for (int i = 0; i < 24; ++i)
              dF[l](i, j) =
                  (plus.response.force[i].lane[l] - minus.response.force[i].lane[l]) / (2.0 * h);
            dE[l][j] = (plus.response.energy.lane[l] - minus.response.energy.lane[l]) / (2.0 * h);
          }
        }
        for (int l = 0; l < kBatchLanes; ++l) {
          ASSERT_TRUE(t.response.ok[l]);
          const ElementMatrix K = lane_stiffness(t, l);
          ElementVector f;
          for (int k = 0; k < 24; ++k) f[k] = t.response.force[k].lane[l];
          EXPECT_LT((dF[l] - K).norm() / K.norm(), 1e-6) << "lane " << l;
          EXPECT_LT((dE[l] - f).norm() / f.norm(), 1e-6) << "lane " << l;
        }
      }
    }
  }
}

TEST(Element, InternalForceIsSelfEquilibratedAndRigidMotionIsStressFree) {
  const auto material = make("mooney_rivlin5", 0.49);
  const hex8::ElementCoords X = reference_element();
  const ElementGeometry geometry = make_element_geometry(X);
  ElementResponse r;
  for (Formulation f : {Formulation::standard, Formulation::mean_dilatation}) {
    ASSERT_TRUE(evaluate_element(geometry, deformed(X), *material, f, false, r));
    Vec3 total = Vec3::Zero();
    for (int a = 0; a < 8; ++a) total += r.force.segment<3>(3 * a);
    // Forces of ~1e-2 N summing to round-off.
    EXPECT_LT(total.norm(), 1e-12 * r.force.norm());

    const Mat3 R = Eigen::AngleAxisd(1.1, Vec3(0.3, -1, 2).normalized()).toRotationMatrix();
    hex8::ElementCoords moved = X * R.transpose();
    moved.rowwise() += Eigen::RowVector3d(0.01, -0.02, 0.03);
    ASSERT_TRUE(evaluate_element(geometry, moved, *material, f, false, r));
    EXPECT_LT(r.force.norm(), 1e-12);  // N: stress round-off ~1e-12 Pa on 1e-4 m^2 faces
    EXPECT_NEAR(r.energy, 0.0, 1e-15);
  }
}

TEST(Element, InvertedElementIsReported) {
  const auto material = make("neo_hookean", 0.3);
  const hex8::ElementCoords X = reference_element();
  const ElementGeometry geometry = make_element_geometry(X);
  hex8::ElementCoords x = X;
  x.row(6) = X.row(0) - Eigen::RowVector3d(0.001, 0.001, 0.001);  // through the opposite corner
  ElementResponse r;
  EXPECT_FALSE(evaluate_element(geometry, x, *material, Formulation::standard, true, r));
  EXPECT_LE(r.min_J, 0.0);
}

TEST(Element, MassAndShapeIntegralsAddUpToVolume) {
  const hex8::ElementCoords X = reference_element();
  const ElementGeometry geometry = make_element_geometry(X);
  EXPECT_NEAR(element_mass_pattern(X).sum(), geometry.volume, 1e-15 * 1e6);
  EXPECT_NEAR(element_shape_integrals(geometry).sum(), geometry.volume, 1e-18);
}

TEST(Element, MeanDilatationNeedsAnUncoupledMaterial) {
  const auto material = make("linear", 0.3);
  const hex8::ElementCoords X = reference_element();
  ElementResponse r;
  EXPECT_THROW(evaluate_element(make_element_geometry(X), X, *material,
                                Formulation::mean_dilatation, false, r),
               std::invalid_argument);
}

}  // namespace
}  // namespace tongue::fem
