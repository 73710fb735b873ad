// Long runs under random activations, through the real sim_server in lock-step:
// every muscle jumps to a random level in [0, 1] at random times (on average every 100 ms).
// Pass: every step converges (the server never accepts one that does not), every published
// position is finite, and no element is inverted (checked here from the published positions
// every 25 steps). Quick: 2 simulated seconds (CI); full (STRESS_FULL, label slow): ten minutes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "random_activation_sequence.hpp"
#include "stress_support.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif
#ifndef STRESS_FULL
#define STRESS_FULL 0
#endif

namespace tongue::stress {
namespace {

constexpr double kDt = 0.004;                             // s
constexpr double kSimulated = STRESS_FULL ? 600.0 : 2.0;  // s
constexpr double kMeanHold = 0.1;                         // s between jumps of one muscle
constexpr unsigned kSeed = 2026;
constexpr int kPort = STRESS_FULL ? 7876 : 7875;

class RandomActivations : public testing::TempDirTest {};

TEST_F(RandomActivations, EveryStepConvergesAndNoElementInverts) {
  const std::string url = testing::bus_url(kPort);
  testing::ServerController controller(url);
  ASSERT_TRUE(controller.good());
  const std::string scene =
      write("scene.yaml", testing::tongue_scene_head() +
                              "analysis: {type: dynamic, settle: true, duration: 1, dt: 0.004}\n");
  testing::ChildProcess server(SIM_SERVER_PATH, {scene, "--lcm-url", url}, dir_);
  const auto model = controller.wait_model(60000);
  ASSERT_TRUE(model) << server.stderr_text();
  ASSERT_TRUE(controller.wait_step(0, 60000)) << server.stderr_text();

  RandomActivationSequence sequence(static_cast<int>(model->muscle_names.size()), kDt, kMeanHold,
                                    kSeed);
  const long steps = std::lround(kSimulated / kDt);
  long cuts = 0;
  double worst = 1e300;
  for (long k = 1; k <= steps; ++k) {
    controller.send_activation(k, model->muscle_names, sequence.next());
    const auto s = controller.wait_step(k, 60000);
    ASSERT_TRUE(s) << "no state for step " << k << "\n" << server.stderr_text();
    ASSERT_TRUE(s->converged) << "step " << k << ": " << s->status;
    cuts += s->step_cuts;
    for (const double x : s->positions) ASSERT_TRUE(std::isfinite(x)) << "step " << k;
    if (k % 25 == 0 || k == steps) {
      const std::vector<int> elements(model->elements.begin(), model->elements.end());
      worst = std::min(
          worst, testing::min_relative_jacobian(model->rest_positions, s->positions, elements));
      ASSERT_GT(worst, 0.0) << "an inverted element at step " << k;
    }
  }
  std::printf(
      "%ld steps (%.0f s simulated), %ld activation jumps, %ld step cuts (reported), "
      "smallest det J / det J0 %.3f\n",
      steps, kSimulated, sequence.jumps(), cuts, worst);
  controller.send_command("shutdown");
  EXPECT_EQ(server.wait_exit(10000), 0) << server.stderr_text();
}

}  // namespace
}  // namespace tongue::stress
