// The run object on a small box with one muscle: the start-up order (settled, at rest, muscles
// off), activations as the step's input, a restart that repeats the run bit for bit, and the
// muscle frame each step returns.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "model/muscle_forces.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run.hpp"
#include "support/box_scenes.hpp"

namespace tongue::scene_run {
namespace {

// The test box (tests/support/box_scenes.hpp), settled under gravity first or not.
scene::Scene box(bool settle) {
  std::string text = testing::kBoxScene;
  const std::string analysis = "dt: 0.002}";
  text.replace(text.find(analysis), analysis.size(),
               std::string("dt: 0.002, settle: ") + (settle ? "true}" : "false}"));
  return scene::parse_scene(text, "", "box.yaml");
}

fem::Vector level(double a) {
  return fem::Vector::Constant(1, a);
}

TEST(SceneRun, StartSettlesUnderGravityWithMusclesOff) {
  const scene::Scene scene = box(true);
  SceneRun run(scene, scene::build_scene(scene));
  const fem::StaticReport settled = run.start();
  ASSERT_TRUE(settled.converged) << settled.message;
  EXPECT_FALSE(settled.increments.empty());
  EXPECT_EQ(run.step_count(), 0);
  EXPECT_EQ(run.time(), 0.0);
  // Gravity bends the free end down before any muscle acts.
  EXPECT_LT(run.displacement().minCoeff(), 0.0);
  EXPECT_EQ(run.displacement(), run.initial_displacement());
  EXPECT_EQ(run.velocity().norm(), 0.0);
  EXPECT_EQ(run.levels(), level(0.0));
  // Settled means at equilibrium: with no muscle acting, a step hardly moves it (the settling's
  // residual tolerance moves a node by far less than a micrometre at this stiffness).
  const StepResult r = run.step(0.002, level(0.0));
  ASSERT_TRUE(r.report.converged) << r.report.message;
  EXPECT_LT((run.displacement() - run.initial_displacement()).lpNorm<Eigen::Infinity>(), 1e-6);
}

TEST(SceneRun, WithoutSettlingStartsFromTheRestState) {
  const scene::Scene scene = box(false);
  SceneRun run(scene, scene::build_scene(scene));
  const fem::StaticReport settled = run.start();
  EXPECT_TRUE(settled.converged);
  EXPECT_TRUE(settled.increments.empty());
  EXPECT_EQ(run.displacement().norm(), 0.0);
}

TEST(SceneRun, StepTakesTheLevelsAndReturnsTheMuscleFrame) {
  const scene::Scene scene = box(true);
  SceneRun run(scene, scene::build_scene(scene));
  ASSERT_TRUE(run.start().converged);
  const StepResult r = run.step(0.002, level(0.5));
  ASSERT_TRUE(r.report.converged) << r.report.message;
  EXPECT_EQ(run.step_count(), 1);
  EXPECT_DOUBLE_EQ(run.time(), 0.002);
  EXPECT_EQ(run.levels(), level(0.5));
  ASSERT_EQ(r.muscles.activations.size(), 1);
  EXPECT_EQ(r.muscles.activations[0], 0.5);
  // The fibre (nodes 2, 3, 4 along x at 10 mm spacing, one fibre: its length is the muscle's)
  // is about 20 mm long, and it moves.
  const model::Fibre& fibre = run.built().muscles->muscles()[0].fibres[0];
  EXPECT_EQ(r.muscles.lengths[0], model::fibre_length(fibre, run.positions()));
  EXPECT_NEAR(r.muscles.lengths[0], 0.02, 1e-3);
  EXPECT_EQ(r.muscles.velocities[0],
            model::fibre_kinematics(fibre, run.positions(), run.velocity()).rate);
  EXPECT_NE(r.muscles.velocities[0], 0.0);
  // The frame of the state reached is the one step() returned.
  const run_file::MuscleFrame now = run.muscle_frame();
  EXPECT_EQ(now.lengths, r.muscles.lengths);
  EXPECT_EQ(now.velocities, r.muscles.velocities);
  EXPECT_FALSE(r.ellipticity_loss);
}

// The first step's tangent is factorized at start-up: the first step forms none, and reaches the
// state an integrator that factorizes in its first step reaches, bit for bit (the same tangent,
// at the same predictor, under the same loads).
TEST(SceneRun, TheFirstStepUsesTheFactorizationMadeAtStart) {
  const scene::Scene scene = box(false);  // not settled: gravity moves it from the first step
  SceneRun run(scene, scene::build_scene(scene));
  ASSERT_TRUE(run.start().converged);
  const StepResult r = run.step(0.002, level(0.0));
  ASSERT_TRUE(r.report.converged) << r.report.message;
  EXPECT_GT(r.report.iterations, 0);
  EXPECT_EQ(r.report.factorizations, 0);

  const scene::BuiltScene built = scene::build_scene(scene);
  fem::NewmarkIntegrator plain(*built.system, built.dynamic_settings);
  plain.initialize(run.initial_displacement(),
                   fem::Vector::Zero(run.initial_displacement().size()));
  const fem::StepReport first = plain.step(0.002);
  ASSERT_TRUE(first.converged) << first.message;
  EXPECT_EQ(first.factorizations, 1);
  EXPECT_EQ(plain.displacement(), run.displacement());
}

// The first step's factor holds the first step's levels whether they were known at start-up (a
// scheduled run) or came with the step (the server): the same states bit for bit, the factor
// formed at start-up in the one and within the first step in the other.
TEST(SceneRun, TheFirstStepsFactorHoldsItsLevelsKnownAtStartOrNot) {
  const scene::Scene scene = box(true);
  SceneRun known(scene, scene::build_scene(scene)), unknown(scene, scene::build_scene(scene));
  ASSERT_TRUE(known.start(level(0.5)).converged);
  ASSERT_TRUE(unknown.start().converged);
  EXPECT_EQ(known.levels(), level(0.0));  // the acceleration is still taken with muscles off
  const StepResult a = known.step(0.002, level(0.5));
  const StepResult b = unknown.step(0.002, level(0.5));
  ASSERT_TRUE(a.report.converged && b.report.converged);
  EXPECT_EQ(a.report.factorizations, 0);
  EXPECT_EQ(b.report.factorizations, 1);
  EXPECT_EQ(known.displacement(), unknown.displacement());
  for (int s = 0; s < 4; ++s) {
    known.step(0.002, level(0.1 * s));
    unknown.step(0.002, level(0.1 * s));
  }
  EXPECT_EQ(known.displacement(), unknown.displacement());
  EXPECT_THROW(known.restart(fem::Vector::Zero(2)), std::invalid_argument);
}

// Levels within SceneRun::kFreshFirstFactor of the start-up factor's keep it: a closed loop
// starting from rest does not pay a factorization for its controller's first small level.
TEST(SceneRun, SmallFirstLevelsKeepTheStartUpFactor) {
  const scene::Scene scene = box(true);
  SceneRun run(scene, scene::build_scene(scene));
  ASSERT_TRUE(run.start().converged);
  const StepResult r = run.step(0.002, level(0.5 * SceneRun::kFreshFirstFactor));
  ASSERT_TRUE(r.report.converged) << r.report.message;
  EXPECT_EQ(r.report.factorizations, 0);
}

TEST(SceneRun, RestartRepeatsTheRunBitForBit) {
  const scene::Scene scene = box(true);
  SceneRun run(scene, scene::build_scene(scene));
  ASSERT_TRUE(run.start().converged);
  const auto drive = [&] {
    for (int s = 0; s < 5; ++s) run.step(0.002, level(s % 2 == 0 ? 1.0 : 0.2));
    return run.displacement();
  };
  const fem::Vector first = drive();
  run.restart();
  EXPECT_EQ(run.step_count(), 0);
  EXPECT_EQ(run.displacement(), run.initial_displacement());
  EXPECT_EQ(run.levels(), level(0.0));
  EXPECT_EQ(drive(), first);
}

// The time is the count of steps times dt, not a running sum: 30 steps of 4 ms end at 0.12 s
// exactly (adding 0.004 thirty times gives 0.12000000000000008); a step of another length counts
// on from the time reached; a restart counts from 0 again.
TEST(SceneRun, TimeIsTheStepCountTimesDt) {
  const scene::Scene scene = box(false);
  SceneRun run(scene, scene::build_scene(scene));
  ASSERT_TRUE(run.start().converged);
  for (int k = 1; k <= 30; ++k) {
    EXPECT_EQ(run.step(0.004, level(0.3)).report.time, k * 0.004);
    EXPECT_EQ(run.time(), k * 0.004);
  }
  EXPECT_EQ(run.time(), 0.12);
  run.step(0.001, level(0.3));
  EXPECT_EQ(run.time(), 0.12 + 0.001);
  run.step(0.001, level(0.3));
  EXPECT_EQ(run.time(), 0.12 + 2 * 0.001);
  run.restart();
  EXPECT_EQ(run.time(), 0.0);
  run.step(0.004, level(0.3));
  EXPECT_EQ(run.time(), 0.004);
}

TEST(SceneRun, RejectsLevelsOfTheWrongSizeOrRangeAndStaticScenes) {
  const scene::Scene scene = box(true);
  SceneRun run(scene, scene::build_scene(scene));
  EXPECT_THROW(run.step(0.002, level(0.0)), std::logic_error);  // before start()
  ASSERT_TRUE(run.start().converged);
  EXPECT_THROW(run.step(0.002, fem::Vector::Zero(2)), std::invalid_argument);
  EXPECT_THROW(run.step(0.002, level(1.5)), std::invalid_argument);
  EXPECT_EQ(run.step_count(), 0);  // nothing was stepped
  // A restart's first levels likewise, refused before the run is touched.
  ASSERT_TRUE(run.step(0.002, level(0.5)).report.converged);
  EXPECT_THROW(run.restart(fem::Vector::Zero(2)), std::invalid_argument);
  EXPECT_THROW(run.restart(level(-0.1)), std::invalid_argument);
  EXPECT_EQ(run.step_count(), 1);

  std::string text = testing::kBoxScene;
  const std::string dynamic = "{type: dynamic, duration: 0.02, dt: 0.002}";
  text.replace(text.find(dynamic), dynamic.size(), "{type: static}");
  const scene::Scene fixed = scene::parse_scene(text, "", "static.yaml");
  EXPECT_THROW(SceneRun(fixed, scene::build_scene(fixed)), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::scene_run
