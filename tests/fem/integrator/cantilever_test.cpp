// A block of tongue tissue (mooney_rivlin5, nu = 0.49, density 1000 kg/m^3) clamped at one end
// and loaded by its own weight: the scene the tongue model is built from, checked for
// convergence under mesh refinement (static) and time-step refinement (dynamic, with the paper's
// Rayleigh damping), for the volume change its bulk modulus implies, and for an integrator
// initialized again.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fem/integrator/newmark_integrator.hpp"
#include "fem/integrator/static_solver.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::fem {
namespace {

const Vec3 kSize(0.03, 0.015, 0.015);  // m
const Vec3 kGravity(0, -9.81, 0);      // m/s^2

struct Cantilever {
  std::shared_ptr<SolidModel> solid;
  std::unique_ptr<MechanicalSystem> system;
  std::vector<int> end_face;
};

Cantilever make_cantilever(int refinement, double nu) {
  Mesh mesh = make_box(Vec3::Zero(), kSize, 2 * refinement, refinement, refinement);
  std::vector<PrescribedDof> clamped;
  for (int n : mesh.node_set("x_min")) {
    for (int c = 0; c < 3; ++c) clamped.push_back({n, c, 0.0});
  }
  Cantilever cantilever;
  cantilever.end_face = mesh.node_set("x_max");
  cantilever.solid = std::make_shared<SolidModel>(
      std::move(mesh), make_material("mooney_rivlin5", {{"poisson_ratio", nu}}),
      Formulation::mean_dilatation, 1000.0, clamped);
  cantilever.system = std::make_unique<MechanicalSystem>(cantilever.solid);
  cantilever.system->add_load(
      std::make_shared<ConstantForce>("gravity", cantilever.solid->body_force(kGravity)));
  return cantilever;
}

// Mean vertical displacement of the free end face [m].
double end_deflection(const Cantilever& c, const Vector& u) {
  double sum = 0.0;
  for (int n : c.end_face) sum += u[3 * n + 1];
  return sum / c.end_face.size();
}

NewtonSettings tight_newton() {
  NewtonSettings s;
  s.residual_rtol = 1e-10;
  s.residual_atol = 1e-12;  // N; the weight is ~3e-2 N
  s.increment_rtol = 1e-10;
  return s;
}

Vector static_equilibrium(const Cantilever& c) {
  StaticSettings settings;
  settings.load_steps = 2;
  settings.newton = tight_newton();
  Vector u = Vector::Zero(c.solid->num_dofs());
  const StaticReport report = solve_static(*c.system, u, settings);
  EXPECT_TRUE(report.converged) << report.message;
  return u;
}

TEST(Cantilever, StaticDeflectionConvergesUnderMeshRefinement) {
  std::vector<double> d;
  std::printf("Gravity cantilever 30 x 15 x 15 mm, mooney_rivlin5, nu = 0.49, static:\n");
  for (int r : {2, 4, 8}) {
    const Cantilever c = make_cantilever(r, 0.49);
    d.push_back(end_deflection(c, static_equilibrium(c)));
    std::printf("  %2d x %d x %d elements: end deflection %.5f mm\n", 2 * r, r, r, d.back() * 1e3);
  }
  // The deflection grows monotonically toward its limit and the differences shrink. The clamped
  // edge of a nearly incompressible block carries a stress singularity, which holds the
  // end deflection's convergence near order 1 instead of the trilinear element's 2 for smooth
  // solutions; 0.75 leaves room for the pre-asymptotic coarse mesh.
  const double ratio = (d[1] - d[0]) / (d[2] - d[1]);
  std::printf("  observed order %.2f\n", std::log2(ratio));
  EXPECT_LT(d[1], d[0]);
  EXPECT_LT(d[2], d[1]);
  EXPECT_GT(std::log2(ratio), 0.75);
  // The finest mesh is within 3 % of the Richardson-extrapolated limit.
  const double limit = d[2] + (d[2] - d[1]) / (ratio - 1.0);
  std::printf("  extrapolated limit %.5f mm\n", limit * 1e3);
  EXPECT_NEAR(d[2], limit, 0.03 * std::abs(limit));
}

TEST(Cantilever, VolumeChangeScalesWithTheBulkModulusNuImplies) {
  // In the nearly incompressible limit the pressure field is fixed by equilibrium, so the
  // volume change is -int p / K dV: proportional to 1 / K up to O(mu / K) corrections.
  // K = 2 mu0 (1 + nu) / (3 (1 - 2 nu)) gives K(0.499) / K(0.49) = 10.06.
  double dv[2];
  const double nus[2] = {0.49, 0.499};
  for (int i = 0; i < 2; ++i) {
    const Cantilever c = make_cantilever(2, nus[i]);
    const Vector u = static_equilibrium(c);
    dv[i] = c.solid->current_volume(u) / c.solid->reference_volume() - 1.0;
    std::printf("  nu = %.3f: volume change %.4e %%\n", nus[i], dv[i] * 100.0);
    EXPECT_LT(std::abs(dv[i]), 0.02);  // the paper's bound on the volume change at nu = 0.49
  }
  const double k_ratio = (1.499 / (1.0 - 2 * 0.499)) / (1.49 / (1.0 - 2 * 0.49));
  // 10 %: the deviatoric correction is O(mu / K) = 1/25 at nu = 0.49.
  EXPECT_NEAR(dv[0] / dv[1], k_ratio, 0.1 * k_ratio);
}

TEST(Cantilever, DynamicResponseConvergesAtSecondOrderInTime) {
  const Cantilever c = make_cantilever(2, 0.49);
  DynamicSettings settings;
  settings.damping.stiffness_coefficient = 0.028;  // s, the paper's Rayleigh beta
  settings.newton = tight_newton();
  const double duration = 0.1;  // s: about half a period of the first bending mode
  std::vector<double> d;
  std::printf("Gravity cantilever released from rest, end deflection at t = %.2f s:\n", duration);
  for (int steps : {20, 40, 80, 160}) {
    NewmarkIntegrator integrator(*c.system, settings);
    for (int n = 0; n < steps; ++n) {
      const StepReport report = integrator.step(duration / steps);
      ASSERT_TRUE(report.converged) << report.message;
    }
    d.push_back(end_deflection(c, integrator.displacement()));
    std::printf("  dt = %.3f ms: %.6f mm\n", duration / steps * 1e3, d.back() * 1e3);
  }
  // Average-acceleration Newmark is second order; the coarsest pair may do better than its
  // asymptotic rate, the finest must be at it.
  for (int i = 0; i + 2 < 4; ++i) {
    const double order = std::log2((d[i + 1] - d[i]) / (d[i + 2] - d[i + 1]));
    std::printf("  observed order %.3f\n", order);
    EXPECT_GT(order, 1.85);
    if (i == 1) {
      EXPECT_LT(order, 2.15);
    }
  }
}

// An integrator initialized again steps as a new one would, bit for bit: from the state of its
// first initialization (its damping's K0 kept) and from another (K0 taken anew: the material is
// nonlinear, so K0 half way to the sagged state differs from K0 at rest, and the block, out of
// equilibrium there, moves).
TEST(Cantilever, InitializedAgainStepsAsANewIntegrator) {
  const Cantilever c = make_cantilever(2, 0.49);
  DynamicSettings settings;
  settings.damping.stiffness_coefficient = 0.028;  // s
  settings.newton = tight_newton();
  const int n = c.solid->num_dofs();
  const Vector rest = Vector::Zero(n), half = 0.5 * static_equilibrium(c);
  const auto run = [&](NewmarkIntegrator& integrator, const Vector& from) {
    integrator.initialize(from, Vector::Zero(n));
    for (int k = 0; k < 5; ++k) {
      const StepReport r = integrator.step(0.004);
      EXPECT_TRUE(r.converged) << r.message;
    }
    return integrator.displacement();
  };
  NewmarkIntegrator reused(*c.system, settings);
  const Vector first = run(reused, rest);
  EXPECT_EQ(run(reused, rest), first);
  NewmarkIntegrator fresh(*c.system, settings);
  const Vector expected = run(fresh, half);
  EXPECT_EQ(run(reused, half), expected);
  EXPECT_NE(expected, first);
}

}  // namespace
}  // namespace tongue::fem
