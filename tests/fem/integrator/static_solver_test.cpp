// The static solver's load stepping: the load factors it reaches are i / n exactly and the last
// is 1, with no extra increment (a factor built by adding 1 / n n times falls short of 1).
#include "fem/integrator/static_solver.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::fem {
namespace {

TEST(StaticSolver, LoadFactorsAreExactFractionsEndingAtOne) {
  // A cube stretched by 10 %: one face held, the opposite one pulled.
  Mesh mesh = make_box(Vec3::Zero(), Vec3::Constant(0.01), 1, 1, 1);
  std::vector<PrescribedDof> prescribed;
  for (int n : mesh.node_set("x_min"))
    for (int c = 0; c < 3; ++c) prescribed.push_back({n, c, 0.0});
  for (int n : mesh.node_set("x_max")) prescribed.push_back({n, 0, 0.001});
  auto solid = std::make_shared<SolidModel>(std::move(mesh), make_material("mooney_rivlin5", {}),
                                            Formulation::mean_dilatation, 1000.0, prescribed);
  MechanicalSystem system(solid);
  for (int n : {3, 7, 10}) {
    StaticSettings settings;
    settings.load_steps = n;
    Vector u = Vector::Zero(solid->num_dofs());
    const StaticReport report = solve_static(system, u, settings);
    ASSERT_TRUE(report.converged) << report.message;
    ASSERT_EQ(report.increments.size(), static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
      EXPECT_EQ(report.increments[i].time, static_cast<double>(i + 1) / n) << n << " steps";
    EXPECT_EQ(report.increments.back().time, 1.0);
  }
}

}  // namespace
}  // namespace tongue::fem
