// Homogeneous deformations solved as boundary-value problems on a mesh with a distorted interior,
// against the closed-form Cauchy stress of each material (Holzapfel 2000, sec. 6.4 for the
// uncoupled laws in principal stretches; the small-strain law by hand):
//  - uniaxial stress: symmetry planes, one face pulled, the other faces free; the lateral stretch
//    and the axial reaction must match the closed form;
//  - simple shear: every boundary node on x = F X; the reactions on the top face give sigma_12
//    and sigma_22 (Poynting effect).
#include <gtest/gtest.h>

#include "fem/integrator/static_solver.hpp"
#include "fem/material/linear_elastic.hpp"
#include "fem/material/material_test_support.hpp"  // from tests/
#include "fem/mesh/boundary_faces.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::fem {
namespace {

using testing::Case;

constexpr double kSide = 0.01;  // m

// A 2 x 2 x 2 cube with its centre node moved off-centre: the elements are distorted but the
// faces stay plane, so homogeneous fields remain exact solutions.
Mesh cube() {
  Mesh mesh = make_box(Vec3::Zero(), Vec3::Constant(kSide), 2, 2, 2);
  mesh.nodes[13] += Vec3(0.0012, -0.0008, 0.0005);  // node (1, 1, 1)
  return mesh;
}

// Closed-form Cauchy stress for the deformation gradient F of an uncoupled material:
// sigma = (2 / J) dev[(W1 + I1b W2) b_bar - W2 b_bar^2] + K (J - 1) I.
Mat3 closed_form_cauchy(const Material& m, const Mat3& F) {
  const double J = F.determinant();
  if (m.as_uncoupled() == nullptr) {  // small strain: sigma = lambda tr(eps) I + 2 mu eps
    const Mat3 eps = 0.5 * (F + F.transpose()) - Mat3::Identity();
    const double mu = m.initial_shear_modulus(), lambda = m.bulk_modulus() - 2.0 * mu / 3.0;
    return lambda * eps.trace() * Mat3::Identity() + 2.0 * mu * eps;
  }
  const Mat3 b = std::pow(J, -2.0 / 3.0) * F * F.transpose();
  const double I1 = b.trace(), I2 = 0.5 * (I1 * I1 - (b * b).trace());
  const auto d = testing::closed_form_derivatives(m, I1, I2);
  const Mat3 s = (d.W1 + I1 * d.W2) * b - d.W2 * b * b;
  return (2.0 / J) * (s - s.trace() / 3.0 * Mat3::Identity()) +
         m.bulk_modulus() * (J - 1.0) * Mat3::Identity();
}

// Lateral stretch t making sigma_22 = 0 under F = diag(l, t, t), by bisection on the closed form.
double lateral_stretch(const Material& m, double l) {
  auto s22 = [&](double t) { return closed_form_cauchy(m, Vec3(l, t, t).asDiagonal())(1, 1); };
  double lo = 0.3, hi = 1.5;
  for (int i = 0; i < 200 && hi - lo > 1e-16; ++i) {
    const double mid = 0.5 * (lo + hi);
    (s22(mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

StaticSettings tight() {
  StaticSettings s;
  s.load_steps = 4;
  // Close to the round-off floor of the residual, which at K / mu = 5000 (nu = 0.4999) with the
  // standard formulation lies near 1e-12 of the initial residual.
  s.newton.residual_rtol = 1e-11;
  s.newton.residual_atol = 1e-15;  // N; the reactions here are 1e-2..1e2 N
  s.newton.increment_rtol = 1e-12;
  return s;
}

Formulation formulation_for(const Material& m) {
  return m.as_uncoupled() ? Formulation::mean_dilatation : Formulation::standard;
}

class HomogeneousDeformation : public ::testing::TestWithParam<Case> {};

TEST_P(HomogeneousDeformation, UniaxialStressMatchesClosedForm) {
  std::shared_ptr<const Material> material = testing::make(GetParam());
  // A finite stretch for the hyperelastic laws; a small one where the linear law is meant to be.
  const double l = material->as_uncoupled() ? 1.3 : 1.001;
  Mesh mesh = cube();
  std::vector<PrescribedDof> prescribed;
  for (int n : mesh.node_set("x_min")) prescribed.push_back({n, 0, 0.0});
  for (int n : mesh.node_set("y_min")) prescribed.push_back({n, 1, 0.0});
  for (int n : mesh.node_set("z_min")) prescribed.push_back({n, 2, 0.0});
  for (int n : mesh.node_set("x_max")) prescribed.push_back({n, 0, (l - 1.0) * kSide});
  const std::vector<int> pulled = mesh.node_set("x_max");
  const int corner = mesh.node_set("y_max").back();  // (L, L, L)
  auto solid = std::make_shared<SolidModel>(std::move(mesh), material, formulation_for(*material),
                                            1000.0, prescribed);
  MechanicalSystem system(solid);
  Vector u = Vector::Zero(solid->num_dofs());
  const StaticReport report = solve_static(system, u, tight());
  ASSERT_TRUE(report.converged) << report.message;

  const double t_exact = lateral_stretch(*material, l);
  const double t_fe = 1.0 + u[3 * corner + 1] / kSide;
  const Mat3 F = Vec3(l, t_exact, t_exact).asDiagonal();
  const double sigma11 = closed_form_cauchy(*material, F)(0, 0);

  Vector r;
  system.residual(u, 1.0, r, nullptr);
  double reaction = 0.0;  // total axial force on the pulled face [N] = sigma_11 x current area
  for (int n : pulled) reaction += r[3 * n];
  // Cauchy stress = force / current area; the small-strain law's stress is per reference area.
  const double area = material->as_uncoupled() ? t_fe * t_fe * kSide * kSide : kSide * kSide;
  const double sigma11_fe = reaction / area;

  // The bound: 1e-8 relative on the Cauchy stress; Newton stops at 1e-11 of the residual.
  EXPECT_NEAR(t_fe, t_exact, 1e-10 * t_exact);
  EXPECT_NEAR(sigma11_fe, sigma11, 1e-8 * std::abs(sigma11));
}

TEST_P(HomogeneousDeformation, SimpleShearMatchesClosedForm) {
  std::shared_ptr<const Material> material = testing::make(GetParam());
  const double gamma = material->as_uncoupled() ? 0.5 : 1e-3;
  Mat3 F = Mat3::Identity();
  F(0, 1) = gamma;
  Mesh mesh = cube();
  std::vector<PrescribedDof> prescribed;
  for (int n : boundary_nodes(mesh)) {
    const Vec3 u = (F - Mat3::Identity()) * mesh.nodes[n];
    for (int k = 0; k < 3; ++k) prescribed.push_back({n, k, u[k]});
  }
  const std::vector<int> top = mesh.node_set("y_max");
  auto solid = std::make_shared<SolidModel>(std::move(mesh), material, formulation_for(*material),
                                            1000.0, prescribed);
  MechanicalSystem system(solid);
  Vector u = Vector::Zero(solid->num_dofs());
  const StaticReport report = solve_static(system, u, tight());
  ASSERT_TRUE(report.converged) << report.message;

  // The top face keeps its area and normal in simple shear, and the edge contributions of the
  // side faces cancel pairwise, so the summed reactions are sigma_12 A and sigma_22 A exactly.
  Vector r;
  system.residual(u, 1.0, r, nullptr);
  Vec3 force = Vec3::Zero();
  for (int n : top) force += r.segment<3>(3 * n);
  const Mat3 sigma = closed_form_cauchy(*material, F);
  const double area = kSide * kSide;
  EXPECT_NEAR(force[0] / area, sigma(0, 1), 1e-8 * std::abs(sigma(0, 1)));
  // sigma_22 is a second-order effect, small beside sigma_12: compare on sigma_12's scale.
  EXPECT_NEAR(force[1] / area, sigma(1, 1), 1e-8 * std::abs(sigma(0, 1)));
}

INSTANTIATE_TEST_SUITE_P(AllMaterials, HomogeneousDeformation,
                         ::testing::ValuesIn(testing::cases(false)),
                         [](const auto& info) { return testing::case_name(info.param); });

}  // namespace
}  // namespace tongue::fem
