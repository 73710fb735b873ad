// Active stiffening adds (ratio - 1) a times the passive elastic response of a muscle's elements.
#include <gtest/gtest.h>

#include "fem/integrator/mechanical_system.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"
#include "model/active_stiffening.hpp"

namespace tongue::model {
namespace {

struct Fixture {
  std::shared_ptr<fem::SolidModel> solid;
  std::shared_ptr<MuscleForces> muscles;
};

// A 3 x 1 x 1 box clamped at x = 0 with one muscle over elements 1 and 2.
Fixture make() {
  fem::Mesh mesh = fem::make_box(fem::Vec3::Zero(), fem::Vec3(0.03, 0.01, 0.01), 3, 1, 1);
  std::vector<fem::PrescribedDof> clamped;
  for (int n : mesh.node_set("x_min"))
    for (int c = 0; c < 3; ++c) clamped.push_back({n, c, 0.0});
  Muscle m{"m", {1, 2}, {Fibre{{1, 2, 3}, std::nullopt, 1.0}}, 1.0};
  Fixture f;
  f.solid = std::make_shared<fem::SolidModel>(mesh, fem::make_material("mooney_rivlin5", {}),
                                              fem::Formulation::mean_dilatation, 1000.0, clamped,
                                              fibre_node_pairs({m}));
  f.muscles = std::make_shared<MuscleForces>(f.solid, std::vector<Muscle>{m});
  return f;
}

fem::Vector deformed(const fem::SolidModel& solid) {
  fem::Vector u = fem::Vector::Zero(solid.num_dofs());
  for (int n = 0; n < solid.mesh().num_nodes(); ++n) {
    const fem::Vec3 X = solid.mesh().nodes[n];
    if (X.x() > 0.0)
      u.segment<3>(3 * n) = fem::Vec3(0.1 * X.x(), -0.2 * X.x() + 0.1 * X.y(), 0.05 * X.z());
  }
  return u;
}

TEST(ActiveStiffening, IdleMusclesAddNothing) {
  const Fixture f = make();
  const ActiveStiffening stiffening(f.solid, f.muscles);
  const fem::Vector u = deformed(*f.solid);
  fem::Vector force = fem::Vector::Zero(u.size());
  fem::SymmetricMatrix K(f.solid->pattern());
  stiffening.add(u, 1.0, force, &K);
  EXPECT_EQ(force.norm(), 0.0);
  for (double v : K.values()) EXPECT_EQ(v, 0.0);
}

TEST(ActiveStiffening, AddsTheScaledPassiveResponseOfTheActiveElements) {
  const Fixture f = make();
  const double ratio = 5.0, a = 0.6, lambda = 0.5;
  f.muscles->set_activation(0, a);
  const ActiveStiffening stiffening(f.solid, f.muscles, ratio);
  const fem::Vector u = deformed(*f.solid);
  fem::Vector force = fem::Vector::Zero(u.size());
  fem::SymmetricMatrix K(f.solid->pattern());
  stiffening.add(u, lambda, force, &K);

  // The same elements assembled by hand: weight (ratio - 1) a lambda on elements 1 and 2.
  const double w = (ratio - 1.0) * a * lambda;
  fem::Vector expected_force = fem::Vector::Zero(u.size());
  fem::SymmetricMatrix expected_K(f.solid->pattern());
  f.solid->add_weighted(u, {0.0, w, w}, expected_force, &expected_K);
  EXPECT_LT((force + expected_force).norm(), 1e-15 * expected_force.norm());  // acts as internal
  for (std::size_t k = 0; k < K.values().size(); ++k)
    EXPECT_EQ(K.values()[k], expected_K.values()[k]);
  EXPECT_GT(expected_force.norm(), 0.0);

  const std::vector<double> scales = stiffening.element_scales();
  EXPECT_DOUBLE_EQ(scales[0], 1.0);
  EXPECT_DOUBLE_EQ(scales[1], 1.0 + (ratio - 1.0) * a);
}

// In a MechanicalSystem the stiffening rides along in the solid's element pass (one evaluation per
// element, weight 1 + (ratio - 1) a): the same residual and tangent as the solid plus add().
TEST(ActiveStiffening, FoldedIntoTheSolidsPassGivesTheSameResidualAndTangent) {
  const Fixture f = make();
  f.muscles->set_activation(0, 0.6);
  auto stiffening = std::make_shared<ActiveStiffening>(f.solid, f.muscles, 5.0);
  fem::MechanicalSystem system(f.solid);
  system.add_load(stiffening);
  const fem::Vector u = deformed(*f.solid);
  fem::Vector r;
  fem::SymmetricMatrix K(f.solid->pattern());
  ASSERT_TRUE(system.residual(u, 1.0, r, &K).ok);

  fem::Vector expected;
  fem::SymmetricMatrix expected_K(f.solid->pattern());
  ASSERT_TRUE(f.solid->assemble(u, expected, &expected_K).ok);
  fem::Vector load = fem::Vector::Zero(u.size());
  stiffening->add(u, 1.0, load, &expected_K);
  expected -= load;
  // (1 + w) f_e against f_e + w f_e: the same sums grouped differently, round-off apart.
  EXPECT_LT((r - expected).norm(), 1e-13 * expected.norm());
  double k_diff = 0.0, k_norm = 0.0;
  for (std::size_t k = 0; k < K.values().size(); ++k) {
    k_diff = std::max(k_diff, std::abs(K.values()[k] - expected_K.values()[k]));
    k_norm = std::max(k_norm, std::abs(expected_K.values()[k]));
  }
  EXPECT_LT(k_diff, 1e-13 * k_norm);
}

// With element weights (a hyper-reduction sample: elements 0 and 1 of weights 2 and 3, element 2
// not sampled) the folded stiffening scales each sampled element's weight by 1 + (ratio - 1) a:
// the stiffening is integrated over the sample, and an unsampled element stays unevaluated
// (an inverted element 2 would otherwise be reported).
TEST(ActiveStiffening, FoldedIntoASampleScalesTheSampledElementsOnly) {
  const Fixture f = make();
  const double ratio = 5.0, a = 0.6;
  f.muscles->set_activation(0, a);
  fem::MechanicalSystem system(f.solid);
  system.add_load(std::make_shared<ActiveStiffening>(f.solid, f.muscles, ratio));
  const fem::Vector u = deformed(*f.solid);
  const std::vector<double> sample{2.0, 3.0, 0.0};
  fem::Vector r;
  fem::SymmetricMatrix K(f.solid->pattern());
  ASSERT_TRUE(system.residual(u, 1.0, r, &K, nullptr, &sample).ok);

  fem::Vector expected = fem::Vector::Zero(u.size());
  fem::SymmetricMatrix expected_K(f.solid->pattern());
  ASSERT_TRUE(
      f.solid->add_weighted(u, {2.0, 3.0 * (1.0 + (ratio - 1.0) * a), 0.0}, expected, &expected_K)
          .ok);
  // The same weights, one product apart: round-off.
  EXPECT_LT((r - expected).norm(), 1e-14 * expected.norm());
  for (std::size_t k = 0; k < K.values().size(); ++k)
    EXPECT_NEAR(K.values()[k], expected_K.values()[k], 1e-14 * std::abs(expected_K.values()[k]));
}

TEST(ActiveStiffening, RejectsARatioBelowOne) {
  const Fixture f = make();
  EXPECT_THROW(ActiveStiffening(f.solid, f.muscles, 0.9), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::model
