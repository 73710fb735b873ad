// The patch test (Irons; Zienkiewicz & Taylor 2000, sec. 9.2): on a distorted mesh, a displacement
// field that the elements can represent exactly, imposed on the boundary, must be reproduced at
// every interior node. For the linear material the field is affine (constant strain); for the
// hyperelastic materials a finite homogeneous deformation is the exact solution too.
#include <gtest/gtest.h>

#include <random>

#include "fem/integrator/static_solver.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/boundary_faces.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::fem {
namespace {

// A 3 x 3 x 3 box of 30 mm whose interior nodes are moved randomly by up to 2 mm.
Mesh distorted_box() {
  Mesh mesh = make_box(Vec3::Zero(), Vec3(0.03, 0.03, 0.03), 3, 3, 3);
  const std::vector<int> boundary = boundary_nodes(mesh);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> shift(-0.002, 0.002);
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    if (!std::binary_search(boundary.begin(), boundary.end(), n)) {
      mesh.nodes[n] += Vec3(shift(rng), shift(rng), shift(rng));
    }
  }
  return mesh;
}

struct PatchCase {
  std::string material;
  Formulation formulation;
  double scale;  // size of the displacement gradient
};

class PatchTest : public ::testing::TestWithParam<PatchCase> {};

TEST_P(PatchTest, InteriorNodesFollowTheImposedHomogeneousField) {
  const PatchCase c = GetParam();
  Mesh mesh = distorted_box();
  Mat3 H;  // displacement gradient
  H << 0.3, 0.1, -0.05, 0.08, -0.2, 0.12, -0.1, 0.05, 0.15;
  H *= c.scale;
  const Vec3 b(0.001, -0.002, 0.0005);
  std::vector<PrescribedDof> prescribed;
  for (int n : boundary_nodes(mesh)) {
    const Vec3 u = H * mesh.nodes[n] + b;
    for (int k = 0; k < 3; ++k) prescribed.push_back({n, k, u[k]});
  }
  std::map<std::string, double> params{{"poisson_ratio", 0.45}};
  if (c.material == "neo_hookean") params["shear_modulus"] = 5e3;
  auto solid = std::make_shared<SolidModel>(mesh, make_material(c.material, params), c.formulation,
                                            1000.0, prescribed);
  MechanicalSystem system(solid);
  StaticSettings settings;
  settings.load_steps = 2;
  settings.newton.residual_rtol = 1e-12;
  settings.newton.residual_atol = 1e-14;  // N; forces here are ~1e-1 N
  Vector u = Vector::Zero(solid->num_dofs());
  const StaticReport report = solve_static(system, u, settings);
  ASSERT_TRUE(report.converged) << report.message;

  double worst = 0.0;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const Vec3 exact = H * mesh.nodes[n] + b;
    worst = std::max(worst, (u.segment<3>(3 * n) - exact).norm() / exact.norm());
  }
  // Exact up to the solver tolerance: 1e-12 of the residual gives ~1e-12 relative displacement,
  // times the condition of the stiffness (~1e2 on this mesh).
  EXPECT_LT(worst, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(
    Materials, PatchTest,
    ::testing::Values(PatchCase{"linear", Formulation::standard, 0.01},
                      PatchCase{"neo_hookean", Formulation::standard, 1.0},
                      PatchCase{"neo_hookean", Formulation::mean_dilatation, 1.0},
                      PatchCase{"mooney_rivlin5", Formulation::mean_dilatation, 1.0},
                      PatchCase{"exponential", Formulation::mean_dilatation, 1.0}),
    [](const auto& info) {
      return info.param.material +
             (info.param.formulation == Formulation::standard ? "_standard" : "_mean_dilatation");
    });

}  // namespace
}  // namespace tongue::fem
