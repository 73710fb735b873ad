// The equilibrium-point controller without a bus: a model and states given by hand, the levels it
// commands checked against the lambda model's formula.
#include "ep_controller/ep_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "controller/input_error.hpp"
#include "ep_controller/force_lag.hpp"

namespace tongue::ep_controller {
namespace {

constexpr double kDt = 0.004;  // s

controller::Model two_halves() {
  controller::Model m;
  m.muscle_names = {"SG_left", "SG_right", "HG_left"};
  m.muscle_max_forces = {12.0, 12.0, 32.5};
  m.num_muscles = 3;
  m.dt = kDt;
  return m;
}

controller::State state(std::int64_t step, double length_m, double velocity_m_s = 0.0) {
  controller::State s;
  s.step = step;
  s.time = static_cast<double>(step) * kDt;
  s.num_muscles = 3;
  s.muscle_lengths = {length_m, length_m, 0.04};
  s.muscle_velocities = {velocity_m_s, velocity_m_s, 0.0};
  return s;
}

// Without the force lag (the bare lambda model) unless lag_s is given.
EpController controller(const std::string& plan, double delay_s = 0.012, bool vf = true,
                        double lag_s = 0.0) {
  EpSettings settings;
  settings.delay_s = delay_s;
  settings.velocity_factor = vf;
  settings.force_lag_s = lag_s;
  return EpController(parse_motor_plan(plan, "plan.yaml"), settings);
}

TEST(EpController, AtRestWithoutAPlanEveryLevelIsZero) {
  EpController c = controller("delta_lambda_mm: {SG: [0]}");
  c.start(two_halves());
  c.observe(state(0, 0.06));
  const controller::MuscleLevels levels = c.command(1);
  EXPECT_EQ(levels.names, two_halves().muscle_names);  // every muscle, every step
  EXPECT_EQ(levels.levels, (std::vector<double>{0.0, 0.0, 0.0}));
}

TEST(EpController, LoweredLambdaGivesTheExponentialForceSplitOverTheHalves) {
  // Transition 0: lambda jumps to rest - 10 mm at once.
  EpController c = controller("transition: 0\ndelta_lambda_mm: {SG: [-10]}");
  c.start(two_halves());
  c.observe(state(0, 0.06));
  const controller::MuscleLevels levels = c.command(1);
  // Each half: rho 4.4 / 2 (equal F_max), A = 10 mm, at rest (velocity factor at 0), F_max 12.
  const double force = 2.2 * std::expm1(0.112 * 10.0) * velocity_factor(0.0);
  EXPECT_NEAR(levels.levels[0], force / 12.0, 1e-12);
  EXPECT_EQ(levels.levels[1], levels.levels[0]);
  EXPECT_EQ(levels.levels[2], 0.0);  // HG: not in the plan, at its rest length
  EXPECT_NEAR(c.last_commands()[0].stretch_mm, 10.0, 1e-9);
}

TEST(EpController, DelayInStepsIsDelayOverDtAndAtLeastOne) {
  for (const auto& [delay_s, steps] : std::vector<std::pair<double, double>>{
           {0.012, 3.0}, {0.010, 2.5}, {0.0, 1.0}, {0.001, 1.0}, {0.020, 5.0}}) {
    EpController c = controller("delta_lambda_mm: {SG: [0]}", delay_s);
    c.start(two_halves());
    EXPECT_NEAR(c.delay_steps(), steps, 1e-12) << delay_s << " s";
  }
}

TEST(EpController, UsesTheFeedbackOfStepKPlusOneMinusDelay) {
  // Plan of zeros: A = l(t - d) - l_rest. The muscle lengthens 1 mm per step from 60 mm.
  EpController c = controller("delta_lambda_mm: {SG: [0]}", 0.012, false);
  c.start(two_halves());
  for (std::int64_t k = 0; k <= 8; ++k) {
    c.observe(state(k, 0.060 + 0.001 * static_cast<double>(k)));
    c.command(k + 1);
    const double delayed_step = static_cast<double>(std::max<std::int64_t>(0, k + 1 - 3));
    EXPECT_NEAR(c.last_commands()[0].stretch_mm, delayed_step, 1e-9) << "step " << k + 1;
  }
}

TEST(EpController, ADelayBetweenStepsInterpolatesTheFeedback) {
  // 10 ms at dt 4 ms is 2.5 steps: the command for step k + 1 sees the length of step
  // k - 1.5, linear in the step here, so the interpolation is exact: A = k - 1.5 mm.
  EpController c = controller("delta_lambda_mm: {SG: [0]}", 0.010, false);
  c.start(two_halves());
  for (std::int64_t k = 0; k <= 8; ++k) {
    c.observe(state(k, 0.060 + 0.001 * static_cast<double>(k), 0.25));
    c.command(k + 1);
    const double delayed_step = std::max(0.0, static_cast<double>(k) - 1.5);
    // mu v = 0.01 s x 250 mm/s = 2.5 mm, interpolated like the length (constant here).
    EXPECT_NEAR(c.last_commands()[0].stretch_mm, delayed_step + 2.5, 1e-9) << "step " << k + 1;
  }
}

TEST(EpController, VelocityEntersThroughMuAndTheFactor) {
  EpController with = controller("delta_lambda_mm: {SG: [0]}", 0.004, true);
  EpController without = controller("delta_lambda_mm: {SG: [0]}", 0.004, false);
  for (EpController* c : {&with, &without}) {
    c->start(two_halves());
    c->observe(state(0, 0.060));
    c->observe(state(1, 0.062, 0.5));  // 2 mm longer, lengthening at 500 mm/s
    c->command(2);
  }
  // A = 2 mm + 0.01 s * 500 mm/s = 7 mm.
  EXPECT_NEAR(without.last_commands()[0].stretch_mm, 7.0, 1e-9);
  const double r = 500.0 / 60.0;  // l'/l0, 1/s
  EXPECT_NEAR(with.last_commands()[0].force_n,
              without.last_commands()[0].force_n * velocity_factor(r), 1e-12);
}

TEST(EpController, ForceLagMakesTheLevelsApproachTheLawExponentially) {
  const double lag_s = 0.05;
  EpController lagged =
      controller("transition: 0\ndelta_lambda_mm: {SG: [-10]}", 0.004, true, lag_s);
  EpController bare = controller("transition: 0\ndelta_lambda_mm: {SG: [-10]}", 0.004, true);
  for (EpController* c : {&lagged, &bare}) {
    c->start(two_halves());
    c->observe(state(0, 0.06));
  }
  const double law = bare.command(1).levels[0];
  ASSERT_GT(law, 0.0);
  // The tongue held still: the law's level rises from 0 at step 0 to `law` at step 1 (the
  // lag's input moves linearly over a step) and stays there, so after k steps the level is
  // law (1 - E^(k - 1) (tau / dt)(1 - E)), E = exp(-dt / tau): the exact response to that
  // input.
  const double e = std::exp(-kDt / lag_s);
  for (int k = 1; k <= 20; ++k) {
    if (k > 1) lagged.observe(state(k - 1, 0.06));
    const double level = lagged.command(k).levels[0];
    EXPECT_NEAR(level, law * (1.0 - std::pow(e, k - 1) * (lag_s / kDt) * (1.0 - e)), 1e-12)
        << "step " << k;
    EXPECT_EQ(lagged.last_commands()[0].level, law);  // the law itself is unchanged
  }
}

TEST(EpController, RestLengthsComeFromTheFirstStateSeen) {
  EpController c = controller("delta_lambda_mm: {SG: [0]}", 0.004, false);
  c.start(two_halves());
  c.observe(state(40, 0.055));  // joined a server at step 40
  c.observe(state(41, 0.056));
  EXPECT_EQ(c.laws()[0].rest_length_mm, 55.0);
  c.command(42);
  EXPECT_NEAR(c.last_commands()[0].stretch_mm, 1.0, 1e-9);
}

TEST(EpController, UnusableFeedbackIsAnError) {
  EpController c = controller("delta_lambda_mm: {SG: [0]}");
  c.start(two_halves());
  EXPECT_THROW(c.observe(state(0, std::numeric_limits<double>::quiet_NaN())), std::runtime_error);
  EXPECT_THROW(c.observe(state(0, 0.0)), std::runtime_error);
  EXPECT_THROW(c.observe(state(0, 0.06, std::numeric_limits<double>::infinity())),
               std::runtime_error);
}

TEST(EpController, PlanThatDoesNotFitTheModelNamesTheFile) {
  EpController unknown = controller("delta_lambda_mm: {GGp: [-5]}");
  EXPECT_THROW(unknown.start(two_halves()), controller::InputError);
  EpController rho = controller("delta_lambda_mm: {SG: [-5]}\nrho: {XX: 1}");
  try {
    rho.start(two_halves());
    ADD_FAILURE() << "accepted";
  } catch (const controller::InputError& e) {
    EXPECT_EQ(e.key_path(), "rho.XX");
  }
  controller::Model box = two_halves();
  box.muscle_names[2] = "flexor";  // no default rho
  EpController no_rho = controller("delta_lambda_mm: {SG: [-5]}");
  try {
    no_rho.start(box);
    ADD_FAILURE() << "accepted";
  } catch (const controller::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("flexor"), std::string::npos) << e.what();
  }
}

TEST(ForceLag, IsExactForAnInputLinearInTime) {
  // tau y' = u - y, y(0) = 0, u = r t: y = r (t - tau + tau exp(-t / tau)) (closed form). The
  // first-order hold reproduces it at every step to round-off, also over skipped steps; the
  // zero-order hold (u held at the step's end) would be off by about r dt / 2 (1 - e^(-t/tau)).
  const double tau = 0.02, dt = 0.004, r = 25.0;  // s, s, 1/s
  ForceLag lag(1, tau, dt);
  for (const int k : {1, 2, 3, 5, 9, 10, 17}) {
    const double t = k * dt;
    const double exact = r * (t - tau + tau * std::exp(-t / tau));
    EXPECT_NEAR(lag.update(k, {r * t})[0], exact, 1e-14) << "step " << k;
  }
}

TEST(ForceLag, SkippedStepsAdvanceByTheirTimeAndAResetStartsFromZero) {
  ForceLag lag(1, 0.02, 0.004);
  const double one = lag.update(1, {1.0})[0];
  // From 0 at step 0 to 1 at step 1: a ramp over the step, 1 - (tau / dt)(1 - E).
  EXPECT_NEAR(one, 1.0 + 0.02 / 0.004 * std::expm1(-0.004 / 0.02), 1e-15);
  // Three steps at once (real time with --publish-every), the input held at 1:
  // exp(-3 dt / tau) of the gap is left.
  const double four = lag.update(4, {1.0})[0];
  EXPECT_NEAR(1.0 - four, (1.0 - one) * std::exp(-3 * 0.004 / 0.02), 1e-15);
  // The server went back to step 0: the lag restarts from 0 as the server's levels do.
  EXPECT_NEAR(lag.update(1, {1.0})[0], one, 1e-15);
  ForceLag none(2, 0.0, 0.004);
  EXPECT_EQ(none.update(1, {0.3, 0.7}), (std::vector<double>{0.3, 0.7}));
  EXPECT_THROW(ForceLag(1, -1.0, 0.004), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::ep_controller
