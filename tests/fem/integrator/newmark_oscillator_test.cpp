// Newmark against the analytic response of a linear spring-mass oscillator: a single hexahedron
// of the small-strain material with every dof fixed but one, so that m = M_ii and k = K_ii exactly
// (the internal force of that material is linear in u). Undamped and with Rayleigh damping
// c = alpha m + beta k, from u(0) = u0, v(0) = 0:
//   u(t) = u0 exp(-zeta w t) (cos(wd t) + zeta w / wd sin(wd t)), zeta = c / (2 m w),
//   wd = w sqrt(1 - zeta^2)  (Clough & Penzien 1993, ch. 2).
// The average-acceleration scheme is second-order accurate: halving dt quarters the error; so is
// the alpha method of Wood, Bossak & Zienkiewicz, which also damps the modes a step cannot
// resolve by its spectral radius a step.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

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
double max_error(const Oscillator& osc, const RayleighDamping& damping, int steps_per_period,
                 const NewmarkParameters& newmark) {
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
  settings.newmark = newmark;
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

void expect_second_order(const RayleighDamping& damping, const char* label,
                         const NewmarkParameters& newmark = {}) {
  const Oscillator osc = make_oscillator();
  ASSERT_GT(osc.m, 0.0);
  ASSERT_GT(osc.k, 0.0);
  std::printf("Newmark oscillator (%s): steps/period, max error [m], observed order\n", label);
  double previous = 0.0;
  for (int steps : {20, 40, 80, 160}) {
    const double e = max_error(osc, damping, steps, newmark);
    const double order = previous > 0.0 ? std::log2(previous / e) : 0.0;
    std::printf("  %4d  %.3e  %.3f\n", steps, e, order);
    // Asymptotically 2; 1.9..2.1 leaves room for the pre-asymptotic coarse steps.
    if (previous > 0.0) {
      EXPECT_GT(order, 1.9);
      EXPECT_LT(order, 2.1);
    }
    previous = e;
  }
  if (newmark.alpha != 0.0) return;
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

TEST(NewmarkOscillator, AlphaMethodIsSecondOrder) {
  expect_second_order({}, "alpha method, rho_inf 0.8", NewmarkParameters::bossak(0.8));
  expect_second_order({}, "alpha method, rho_inf 0.5", NewmarkParameters::bossak(0.5));
}

// A mode far too stiff for the step (omega dt = 1000): the spectral radius of one step's
// amplification matrix, which maps (u, v, a) at t_n to t_{n+1}, measured column by column from
// unit states and its eigenvalues taken by Eigen. The average-acceleration rule keeps such a
// mode for ever (radius 1); the alpha method shrinks it by rho_inf a step. At finite omega dt
// the radius differs from its limit by O(1 / (omega dt)): 0.2 % is allowed.
TEST(NewmarkOscillator, AlphaMethodDampsUnresolvedModesByItsSpectralRadius) {
  const Oscillator osc = make_oscillator();
  const double dt = 1000.0 / std::sqrt(osc.k / osc.m);
  for (const double rho : {1.0, 0.8, 0.6, 0.5}) {
    MechanicalSystem system(osc.solid);
    DynamicSettings settings;
    settings.newmark = NewmarkParameters::bossak(rho);
    settings.newton.residual_rtol = 1e-14;  // a linear problem: one Newton step is exact
    Eigen::Matrix3d A;
    for (int column = 0; column < 3; ++column) {
      NewmarkIntegrator integrator(system, settings);
      Vector state[3] = {Vector::Zero(24), Vector::Zero(24), Vector::Zero(24)};
      state[column][osc.dof] = 1e-6;  // small enough for no element to invert
      integrator.initialize(state[0], state[1], state[2], 0.0, Vector::Zero(24));
      ASSERT_TRUE(integrator.step(dt).converged);
      A.col(column) << integrator.displacement()[osc.dof], integrator.velocity()[osc.dof],
          integrator.acceleration()[osc.dof];
      A.col(column) /= 1e-6;
    }
    const double radius = A.eigenvalues().cwiseAbs().maxCoeff();
    std::printf("rho_inf %.2f: spectral radius %.5f at omega dt = 1000\n", rho, radius);
    EXPECT_NEAR(radius, rho, 2e-3 * rho);
  }
}

TEST(NewmarkOscillator, AlphaMethodParameters) {
  // rho_inf = 1 is the average-acceleration rule; rho_inf = 1/2 the smallest alpha, -1/3.
  const NewmarkParameters one = NewmarkParameters::bossak(1.0);
  EXPECT_EQ(one.alpha, 0.0);
  EXPECT_EQ(one.beta, 0.25);
  EXPECT_EQ(one.gamma, 0.5);
  const NewmarkParameters half = NewmarkParameters::bossak(0.5);
  EXPECT_NEAR(half.alpha, -1.0 / 3.0, 1e-15);
  EXPECT_NEAR(half.gamma, 0.5 + 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(half.beta, 4.0 / 9.0, 1e-15);
  EXPECT_THROW(NewmarkParameters::bossak(0.4), std::invalid_argument);
  EXPECT_THROW(NewmarkParameters::bossak(1.1), std::invalid_argument);
  const Oscillator osc = make_oscillator();
  MechanicalSystem system(osc.solid);
  DynamicSettings settings;
  settings.newmark.alpha = 0.1;  // positive: would amplify
  EXPECT_THROW(NewmarkIntegrator(system, settings), std::invalid_argument);
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
