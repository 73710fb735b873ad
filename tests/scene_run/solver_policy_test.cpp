// The dynamic solver's policies (docs/speed.md) on the built-in tongue, through its scenes: a
// tongue at rest costs nothing per step and a change of activation is never skipped; the reused
// factorization (the default) reaches the state full Newton reaches; the default acceptance
// keeps each step within its tolerance; two threads give the run of one bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run.hpp"

namespace tongue::scene_run {
using scene::build_scene;
using scene::dynamic_newton_settings;
using scene::read_scene;
using scene::Scene;
namespace {

Scene tongue_scene(const std::string& name) {
  return read_scene("../../scenes/" + name + ".yaml");
}

// A scene settled and ready to step, as sim_batch runs it.
struct SettledRun {
  explicit SettledRun(const Scene& scene) : run(scene, build_scene(scene)) {
    const fem::StaticReport settled = run.start();
    EXPECT_TRUE(settled.converged) << settled.message;
  }
  // One step of dt with the schedule's levels at its end time.
  fem::StepReport step(double dt) { return step(dt, levels_at(run.time() + dt)); }
  fem::StepReport step(double dt, const fem::Vector& levels) {
    const fem::StepReport r = run.step(dt, levels).report;
    EXPECT_TRUE(r.converged) << r.message;
    return r;
  }
  fem::Vector levels_at(double t) const { return run.built().activations.levels_at(t); }
  scene_run::SceneRun run;
};

double max_nodal_distance(const fem::Vector& a, const fem::Vector& b) {
  double d = 0.0;
  for (Eigen::Index n = 0; n < a.size() / 3; ++n)
    d = std::max(d, (a.segment<3>(3 * n) - b.segment<3>(3 * n)).norm());
  return d;
}

TEST(SolverPolicy, TongueAtRestCostsNothingPerStepAndAChangeIsNeverSkipped) {
  const Scene scene = tongue_scene("tongue_rest");
  SettledRun run(scene);
  const double dt = scene.analysis.dt;
  // The settled state's residual is at the settling's tolerance; the first steps may iterate
  // to bring it to the dynamic one. Once a step starts in equilibrium and nothing moves, the
  // next ones under the same activations are the identity: nothing evaluated.
  for (int s = 0; s < 3; ++s) run.step(dt);
  ASSERT_TRUE(run.run.integrator().at_rest());
  const fem::Vector rest = run.run.displacement();
  for (int s = 0; s < 20; ++s) {
    const double t = run.run.time();
    const fem::StepReport r = run.step(dt);
    EXPECT_TRUE(r.held) << "step " << s;
    EXPECT_EQ(r.iterations, 0) << "step " << s;
    EXPECT_EQ(r.residual_evaluations, 0) << "step " << s;
    EXPECT_EQ(r.factorizations, 0) << "step " << s;
    EXPECT_DOUBLE_EQ(run.run.time(), t + dt);  // the time still advances
    EXPECT_EQ(run.run.time(), static_cast<double>(run.run.step_count()) * dt);
  }
  EXPECT_EQ(run.run.displacement(), rest);

  // A change of activation, however small in the force it adds (1e-4 of SG's 24 N: 2.4 mN, still
  // far above the residual tolerance), is solved, not skipped; and the tongue it sets moving is
  // solved under the same levels too until it is at rest again.
  const int sg = run.run.built().muscles->index_of("SG_left");
  ASSERT_GE(sg, 0);
  fem::Vector levels = run.levels_at(run.run.time() + dt);
  levels[sg] = 1e-4;
  fem::StepReport r = run.step(dt, levels);
  EXPECT_FALSE(r.held);
  EXPECT_GE(r.iterations, 1);
  r = run.step(dt, levels);
  EXPECT_FALSE(r.held);
  EXPECT_GE(r.residual_evaluations, 1);
}

fem::Vector run_sg(Scene scene, int steps) {
  SettledRun run(scene);
  for (int s = 0; s < steps; ++s) run.step(scene.analysis.dt);
  return run.run.displacement();
}

// Both judged by a displacement tolerance far below the default one, so that what is compared is
// where the iterations lead, not where they stop.
Scene converged(Scene scene) {
  scene.solver.displacement_tolerance = 1e-10;  // m
  scene.solver_keys.insert("displacement_tolerance");
  return scene;
}

TEST(SolverPolicy, ReusedFactorizationReachesTheFullNewtonState) {
  Scene reuse = converged(tongue_scene("tongue_sg_3n"));
  Scene full = reuse;
  full.solver.max_tangent_reuse = 0;
  full.solver_keys.insert("max_tangent_reuse");
  ASSERT_GT(dynamic_newton_settings(reuse).max_tangent_reuse, 0);  // the default policy
  ASSERT_EQ(dynamic_newton_settings(full).max_tangent_reuse, 0);
  const int steps = 15;  // 60 ms of the 120 ms: the tongue is moving fastest
  const double d = max_nodal_distance(run_sg(reuse, steps), run_sg(full, steps));
  std::printf("  max nodal distance reuse - full Newton: %.3g um\n", d * 1e6);
  // Both stop where the error left in x is below 1e-10 m per step; over 15 steps, with
  // damping, well below 0.1 um = 1e-7 m, 1000 times below the benchmark's accuracy target.
  EXPECT_LT(d, 1e-7);
}

// The default acceptance (a step's estimated error below dt^2/4 x 2.5 m/s^2 = 10 um at 4 ms) keeps
// the run within that error per step of the converged one: after 15 steps of the fastest motion
// no node is further from it than 15 such errors would put it if none were damped.
TEST(SolverPolicy, DefaultAcceptanceKeepsEachStepWithinItsTolerance) {
  const Scene defaults = tongue_scene("tongue_sg_3n");
  const double tolerance = dynamic_newton_settings(defaults).displacement_tolerance;
  EXPECT_DOUBLE_EQ(tolerance, scene::kDynamicAccelerationTolerance * 0.25 * defaults.analysis.dt *
                                  defaults.analysis.dt);  // m; Newmark beta = 1/4
  const int steps = 15;
  const double d = max_nodal_distance(run_sg(defaults, steps), run_sg(converged(defaults), steps));
  std::printf("  max nodal distance default - converged: %.3g um\n", d * 1e6);
  // sqrt(3): the tolerance bounds each component, the distance is a node's.
  EXPECT_LT(d, steps * std::sqrt(3.0) * tolerance);
}

TEST(SolverPolicy, TwoThreadsGiveTheSameRunAsOne) {
  Scene one = tongue_scene("tongue_sg_3n");
  Scene two = one;
  two.threads = 2;
  const int steps = 5;
  // Elements are evaluated in parallel but summed in element order: the same bits.
  EXPECT_EQ(run_sg(one, steps), run_sg(two, steps));
}

}  // namespace
}  // namespace tongue::scene_run
