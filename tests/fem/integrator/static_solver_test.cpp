// The static solver's load stepping: the load factors it reaches are i / n exactly and the last
// is 1, with no extra increment (a factor built by adding 1 / n n times falls short of 1).
#include "fem/integrator/static_solver.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "fem/assembly/loads.hpp"
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

// A cube whose conditions leave rigid motions free fails before any Newton iteration, naming
// them; with none prescribed, all six.
TEST(StaticSolver, ABodyFreeToMoveRigidlyIsRefusedNamingTheMotions) {
  const auto solve = [](const std::vector<PrescribedDof>& prescribed) {
    Mesh mesh = make_box(Vec3::Zero(), Vec3::Constant(0.01), 1, 1, 1);
    auto solid = std::make_shared<SolidModel>(
        std::move(mesh), make_material("neo_hookean", {{"shear_modulus", 1e3}}),
        Formulation::mean_dilatation, 1000.0, prescribed);
    MechanicalSystem system(solid);
    system.add_load(
        std::make_shared<ConstantForce>("gravity", solid->body_force(Vec3(0.0, -9.81, 0.0))));
    Vector u = Vector::Zero(solid->num_dofs());
    return solve_static(system, u, StaticSettings{});
  };
  StaticReport r = solve({});
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.increments.empty());
  EXPECT_EQ(r.message,
            "the model is free to move as a rigid body (translation along x; translation along "
            "y; translation along z; rotation about x through (0.005, 0.005, 0.005) m; rotation "
            "about y through (0.005, 0.005, 0.005) m; rotation about z through (0.005, 0.005, "
            "0.005) m): its constraints must hold it for a static solution");
  // The bottom face held in y only: it can slide in x and z and turn about y.
  Mesh mesh = make_box(Vec3::Zero(), Vec3::Constant(0.01), 1, 1, 1);
  std::vector<PrescribedDof> bottom;
  for (int n : mesh.node_set("y_min")) bottom.push_back({n, 1, 0.0});
  r = solve(bottom);
  EXPECT_EQ(r.message,
            "the model is free to move as a rigid body (translation along x; translation along "
            "z; rotation about y through (0.005, 0.005, 0.005) m): its constraints must hold it "
            "for a static solution");
  // One node fixed, another held in two components: a hinge through the first node, off the
  // centroid, leaves one rotation that is none of the six.
  r = solve({{0, 0, 0.0}, {0, 1, 0.0}, {0, 2, 0.0}, {1, 1, 0.0}, {1, 2, 0.0}});
  EXPECT_NE(r.message.find("(1 rigid motion combining translations and rotations)"),
            std::string::npos)
      << r.message;
}

}  // namespace
}  // namespace tongue::fem
