// Newmark against the analytic response of a linear spring-mass oscillator: a single hexahedron
// of the small-strain material with every dof fixed but one, so that m = M_ii and k = K_ii exactly
// (the internal force of that material is linear in u). Undamped and with Rayleigh damping
// c = alpha m + beta k, from u(0) = u0, v(0) = 0:
//   u(t) = u0 exp(-zeta w t) (cos(wd t) + zeta w / wd sin(wd t)), zeta = c / (2 m w),
//   wd = w sqrt(1 - zeta^2)  (Clough & Penzien 1993, ch. 2).
// The average-acceleration scheme is second-order accurate: halving dt quarters the error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fem/integrator/newmark_integrator.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::fem {
namespace {

struct Oscillator {
  std::shared_ptr<SolidModel> solid;
  int dof;      // the one free dof
  double m, k;  // its mass [kg] and stiffness [N/m]
};

Oscillator make_oscillator() {
  Mesh mesh = make_box(Vec3::Zero(), Vec3::Constant(0.01), 1, 1, 1);
  const int free_dof = 3 * 6 + 0;  // node 6 = (L, L, L), x component
  std::vector<PrescribedDof> prescribed;
  for (int dof = 0; dof < 24; ++dof) {
    if (dof != free_dof) prescribed.push_back({dof / 3, dof % 3, 0.0});
  }
  auto solid = std::make_shared<SolidModel>(
      std::move(mesh), make_material("linear", {{"youngs_modulus", 15e3}, {"poisson_ratio", 0.3}}),
      Formulation::standard, 1000.0, prescribed);
  SymmetricMatrix K(solid->pattern());
  Vector f;
  solid->assemble(Vector::Zero(24), f, &K);
  return {solid, free_dof, solid->mass_matrix(false).diagonal(0), K.diagonal(0)};
}

// Largest deviation from the analytic response over two periods [m].
double max_error(const Oscillator& osc, const RayleighDamping& damping, int steps_per_period) {
  const double w = std::sqrt(osc.k / osc.m), period = 2.0 * M_PI / w;
  const double c = damping.mass_coefficient * osc.m + damping.stiffness_coefficient * osc.k;
  const double zeta = c / (2.0 * osc.m * w), wd = w * std::sqrt(1.0 - zeta * zeta);
  const double u0 = 1e-4;
  auto exact = [&](double t) {
    return u0 * std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t));
  };

  MechanicalSystem system(osc.solid);
  DynamicSettings settings;
  settings.damping = damping;
  settings.newton.residual_rtol = 1e-14;  // a linear problem: one Newton step is exact
  NewmarkIntegrator integrator(system, settings);
  Vector u0_full = Vector::Zero(24);
  u0_full[osc.dof] = u0;
  integrator.initialize(u0_full, Vector::Zero(24));
  const double dt = period / steps_per_period;
  double worst = 0.0;
  for (int n = 0; n < 2 * steps_per_period; ++n) {
    const StepReport report = integrator.step(dt);
    EXPECT_TRUE(report.converged) << report.message;
    worst =
        std::max(worst, std::abs(integrator.displacement()[osc.dof] - exact(integrator.time())));
  }
  return worst;
}

void expect_second_order(const RayleighDamping& damping, const char* label) {
  const Oscillator osc = make_oscillator();
  ASSERT_GT(osc.m, 0.0);
  ASSERT_GT(osc.k, 0.0);
  std::printf("Newmark oscillator (%s): steps/period, max error [m], observed order\n", label);
  double previous = 0.0;
  for (int steps : {20, 40, 80, 160}) {
    const double e = max_error(osc, damping, steps);
    const double order = previous > 0.0 ? std::log2(previous / e) : 0.0;
    std::printf("  %4d  %.3e  %.3f\n", steps, e, order);
    // Asymptotically 2; 1.9..2.1 leaves room for the pre-asymptotic coarse steps.
    if (previous > 0.0) {
      EXPECT_GT(order, 1.9);
      EXPECT_LT(order, 2.1);
    }
    previous = e;
  }
  // The error is the scheme's period elongation dT / T = (w dt)^2 / 12 (Hughes 2000, sec. 9.3.2):
  // over two periods a phase lag of 4 pi (w dt)^2 / 12, i.e. an amplitude error of u0 times that
  // (smaller with damping, which shrinks the amplitude).
  const double w_dt = 2.0 * M_PI / 160;
  const double predicted = 1e-4 * 4.0 * M_PI * w_dt * w_dt / 12.0;
  EXPECT_LT(previous, 1.05 * predicted);
}

TEST(NewmarkOscillator, UndampedIsSecondOrder) {
  expect_second_order({}, "undamped");
}

TEST(NewmarkOscillator, RayleighDampedIsSecondOrder) {
  // alpha and beta chosen so that zeta ~ 0.1 for this oscillator (w ~ 2e2 rad/s).
  const Oscillator osc = make_oscillator();
  const double w = std::sqrt(osc.k / osc.m);
  expect_second_order({0.1 * w, 0.1 / w}, "Rayleigh damped");
}

TEST(NewmarkOscillator, InitialAccelerationIsConsistent) {
  const Oscillator osc = make_oscillator();
  MechanicalSystem system(osc.solid);
  NewmarkIntegrator integrator(system, DynamicSettings{});
  Vector u0 = Vector::Zero(24);
  u0[osc.dof] = 1e-4;
  integrator.initialize(u0, Vector::Zero(24));
  EXPECT_NEAR(integrator.acceleration()[osc.dof], -osc.k / osc.m * 1e-4,
              1e-12 * osc.k / osc.m * 1e-4);
}

}  // namespace
}  // namespace tongue::fem
