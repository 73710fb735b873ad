// Runs the real sim_server executable on a real LCM bus (udpm on the loopback) with a small box
// scene; the test is the controller: it receives the model and the states, sends activations and
// commands, and reads the run file back with run_file's reader.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "bus/channels.hpp"
#include "bus/messages.hpp"
#include "scene/scene_reader.hpp"
#include "support/reduced_box.hpp"
#include "support/run_command.hpp"
#include "support/run_file.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif

namespace tongue::server {
namespace {

namespace fs = std::filesystem;
using tongue_lcm::lcmt_tongue_model;
using tongue_lcm::lcmt_tongue_state;

constexpr double kDt = 0.002;      // s, the scene's
constexpr int kExitWaitMs = 5000;  // longest wait for the server to exit

using testing::bus_url;
using testing::ChildProcess;
using testing::kBoxScene;
using testing::ServerController;

using testing::RunFile;

class SimServer : public testing::TempDirTest {
 protected:
  // Starts the server in lock-step mode on port with the run file run.h5 (plus extra arguments)
  // after the controller has subscribed.
  void start(int port, const std::vector<std::string>& extra = {},
             const std::string& scene = kBoxScene) {
    url_ = bus_url(port);
    controller_ = std::make_unique<ServerController>(url_);
    ASSERT_TRUE(controller_->good());
    std::vector<std::string> args{write("scene.yaml", scene), "--lcm-url", url_, "--output",
                                  (dir_ / "run.h5").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    server_ = std::make_unique<ChildProcess>(SIM_SERVER_PATH, args, dir_);
    ASSERT_TRUE(server_->started());
  }

  // Sends the activation tagged step with level, and returns the state of that step.
  lcmt_tongue_state step_to(std::int64_t step, double level) {
    controller_->send_activation(step, {"flexor"}, {level});
    const auto s = controller_->wait_step(step);
    EXPECT_TRUE(s) << "no state for step " << step << "\n" << server_->stderr_text();
    return s ? *s : lcmt_tongue_state{};
  }

  // Sends shutdown and returns the exit status (-1: did not exit in time).
  int shut_down() {
    controller_->send_command("shutdown");
    return server_->wait_exit(kExitWaitMs).value_or(-1);
  }

  std::string url_;
  std::unique_ptr<ServerController> controller_;
  std::unique_ptr<ChildProcess> server_;
};

TEST_F(SimServer, LockStepAdvancesOneStepPerActivationAndShutsDownCleanly) {
  start(7701);
  const auto model = controller_->wait_model();
  ASSERT_TRUE(model) << server_->stderr_text();
  EXPECT_EQ(model->num_nodes, 20);
  EXPECT_EQ(model->num_elements, 4);
  EXPECT_EQ(model->muscle_names, (std::vector<std::string>{"flexor"}));
  EXPECT_EQ(model->muscle_max_forces, (std::vector<double>{0.01}));
  EXPECT_DOUBLE_EQ(model->dt, kDt);
  const auto s0 = controller_->wait_step(0);
  ASSERT_TRUE(s0) << server_->stderr_text();
  EXPECT_EQ(s0->num_nodes, 20);
  EXPECT_EQ(s0->positions, model->rest_positions);  // not settled: starts at rest
  EXPECT_EQ(s0->activations, (std::vector<double>{0.0}));
  EXPECT_DOUBLE_EQ(s0->muscle_lengths.at(0), 0.02);  // two 10 mm segments

  constexpr int kSteps = 10;
  for (int k = 1; k <= kSteps; ++k) {
    const lcmt_tongue_state s = step_to(k, 0.1 * k / kSteps + 0.4);
    ASSERT_EQ(s.step, k);
    EXPECT_NEAR(s.time, k * kDt, 1e-12);
    EXPECT_EQ(s.activations, (std::vector<double>{0.1 * k / kSteps + 0.4}));
    EXPECT_TRUE(s.converged);
    EXPECT_EQ(s.status, "ok");
    EXPECT_EQ(s.rejected_messages, 0);
    EXPECT_EQ(s.num_positions, 60);
    EXPECT_EQ(s.muscle_velocities.size(), 1u);
    EXPECT_GT(s.newton_iterations, 0);
  }
  // describe publishes the model again, then the current state (for a late controller).
  controller_->send_command("describe");
  EXPECT_TRUE(controller_->wait_model());
  const auto again = controller_->wait_step(kSteps);
  ASSERT_TRUE(again) << server_->stderr_text();
  EXPECT_EQ(again->status, "ok");

  EXPECT_EQ(shut_down(), 0) << server_->stderr_text();
  const RunFile f(dir_ / "run.h5");
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.doubles("/time").size(), static_cast<std::size_t>(kSteps + 1));
  EXPECT_EQ(f.doubles("/activations").back(), 0.5);
  EXPECT_EQ(f.string_attribute("/", "status"), "completed");
}

TEST_F(SimServer, AReducedModelPublishesItsIndicator) {
  // The box's reduced model (trained on its full model), checked every 3 steps off the step's
  // path, each check reported with the step that hands over the next: each state carries the
  // indicator of the last check reported, 0 before the first (at step 6, of step 3); the run
  // file the same.
  const std::string basis = (dir_ / "basis.h5").string();
  testing::write_reduced_basis_of(scene::parse_scene(kBoxScene, "", "box.yaml"), 40, basis);
  start(7719, {}, std::string(kBoxScene) + "model: {reduced: '" + basis + "', check_every: 3}\n");
  ASSERT_TRUE(controller_->wait_model()) << server_->stderr_text();
  const auto s0 = controller_->wait_step(0);
  ASSERT_TRUE(s0) << server_->stderr_text();
  EXPECT_EQ(s0->reduced_model_correction, 0.0);
  double last = 0.0;
  for (int k = 1; k <= 9; ++k) {
    const lcmt_tongue_state s = step_to(k, 0.7);
    ASSERT_TRUE(s.converged) << s.status;
    if (k < 6) {
      EXPECT_EQ(s.reduced_model_correction, 0.0) << "step " << k;
    }
    if (k == 6 || k == 9) {
      EXPECT_GT(s.reduced_model_correction, 0.0) << "step " << k;
      EXPECT_LT(s.reduced_model_correction, 1e-4) << "step " << k;  // m, far below 1 mm
      EXPECT_NE(s.reduced_model_correction, last) << "step " << k;  // another state's
    }
    if (k == 7 || k == 8) {
      EXPECT_EQ(s.reduced_model_correction, last) << "step " << k;
    }
    last = s.reduced_model_correction;
  }
  EXPECT_EQ(shut_down(), 0) << server_->stderr_text();
  const RunFile f(dir_ / "run.h5");
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.doubles("/solver/reduced_correction").back(), last);
}

// A bad activation message is counted and changes nothing: after it, a pause publishes the
// state again (same step, positions and activations, one more rejection), and the next valid
// activation still advances.
struct BadActivation {
  const char* name;
  int port;
  std::function<void(ServerController&)> send;  // sent when the server is at step 1
};

void PrintTo(const BadActivation& bad, std::ostream* os) {
  *os << bad.name;
}

class SimServerRejects : public SimServer, public ::testing::WithParamInterface<BadActivation> {};

TEST_P(SimServerRejects, CountsTheMessageAndLeavesTheStateUnchanged) {
  start(GetParam().port);
  ASSERT_TRUE(controller_->wait_step(0)) << server_->stderr_text();
  const lcmt_tongue_state s1 = step_to(1, 0.5);
  ASSERT_EQ(s1.step, 1);
  GetParam().send(*controller_);
  controller_->send_command("pause");
  const auto paused =
      controller_->wait_state([](const lcmt_tongue_state& s) { return s.status == "paused"; });
  ASSERT_TRUE(paused) << server_->stderr_text();
  EXPECT_EQ(paused->rejected_messages, 1);
  EXPECT_EQ(paused->step, 1);
  EXPECT_EQ(paused->positions, s1.positions);
  EXPECT_EQ(paused->activations, s1.activations);
  controller_->send_command("resume");
  const lcmt_tongue_state s2 = step_to(2, 0.25);
  EXPECT_EQ(s2.step, 2);
  EXPECT_EQ(s2.activations, (std::vector<double>{0.25}));
  EXPECT_EQ(s2.rejected_messages, 1);
  EXPECT_EQ(shut_down(), 0) << server_->stderr_text();
  EXPECT_NE(server_->stderr_text().find("rejected"), std::string::npos) << server_->stderr_text();
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, SimServerRejects,
    ::testing::Values(
        BadActivation{"UnknownName", 7702,
                      [](ServerController& c) { c.send_activation(2, {"extensor"}, {0.5}); }},
        BadActivation{"NaNLevel", 7703,
                      [](ServerController& c) {
                        c.send_activation(2, {"flexor"},
                                          {std::numeric_limits<double>::quiet_NaN()});
                      }},
        BadActivation{"StaleStep", 7704,
                      [](ServerController& c) { c.send_activation(1, {"flexor"}, {0.9}); }},
        BadActivation{"FutureStep", 7705,
                      [](ServerController& c) { c.send_activation(3, {"flexor"}, {0.9}); }},
        BadActivation{"ApplyNowInLockStep", 7706,
                      [](ServerController& c) { c.send_activation(-1, {"flexor"}, {0.9}); }}),
    [](const ::testing::TestParamInfo<BadActivation>& info) { return info.param.name; });

// Two lock-step runs with the same activations give bit-identical positions.
TEST_F(SimServer, LockStepRunsAreDeterministic) {
  std::vector<std::vector<double>> positions;
  for (int run = 0; run < 2; ++run) {
    start(7707 + run);
    ASSERT_TRUE(controller_->wait_step(0)) << server_->stderr_text();
    for (int k = 1; k <= 8; ++k) ASSERT_EQ(step_to(k, (k % 3) / 2.0).step, k);
    ASSERT_EQ(shut_down(), 0) << server_->stderr_text();
    const RunFile f(dir_ / "run.h5");
    positions.push_back(f.doubles("/positions"));
    ASSERT_EQ(positions.back().size(), 9u * 60u);
  }
  EXPECT_EQ(positions[0], positions[1]);
}

TEST_F(SimServer, ResetReturnsToTheInitialStateAndRepeatsTheRun) {
  start(7709);
  const auto s0 = controller_->wait_step(0);
  ASSERT_TRUE(s0) << server_->stderr_text();
  const lcmt_tongue_state first = step_to(1, 0.7);
  step_to(2, 0.7);
  controller_->send_command("reset");
  const auto again = controller_->wait_step(0);
  ASSERT_TRUE(again) << server_->stderr_text();
  EXPECT_EQ(again->positions, s0->positions);
  EXPECT_EQ(again->activations, (std::vector<double>{0.0}));
  const lcmt_tongue_state repeated = step_to(1, 0.7);
  EXPECT_EQ(repeated.positions, first.positions);
  EXPECT_EQ(shut_down(), 0) << server_->stderr_text();
}

TEST_F(SimServer, SilenceStopsTheServerWhenAskedTo) {
  start(7710, {"--timeout-ms", "200", "--on-silence", "stop"});
  ASSERT_TRUE(controller_->wait_step(0)) << server_->stderr_text();
  EXPECT_EQ(server_->wait_exit(kExitWaitMs), 3);
  EXPECT_NE(server_->stderr_text().find("no activation for step 1 within 200 ms"),
            std::string::npos)
      << server_->stderr_text();
  const RunFile f(dir_ / "run.h5");
  EXPECT_EQ(f.string_attribute("/", "status"), "stopped: no activation for 200 ms");
}

TEST_F(SimServer, SigtermClosesTheRunFile) {
  start(7711);
  ASSERT_TRUE(controller_->wait_step(0)) << server_->stderr_text();
  step_to(1, 0.5);
  server_->signal(SIGTERM);
  EXPECT_EQ(server_->wait_exit(kExitWaitMs), 130);
  const RunFile f(dir_ / "run.h5");
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.doubles("/time").size(), 2u);
  EXPECT_EQ(f.string_attribute("/", "status"), "interrupted");
}

TEST_F(SimServer, FastModeRunsFreelyToMaxSteps) {
  start(7712, {"--mode", "fast", "--max-steps", "30"});
  EXPECT_EQ(server_->wait_exit(kExitWaitMs), 0) << server_->stderr_text();
  EXPECT_TRUE(controller_->wait_step(30));
  const RunFile f(dir_ / "run.h5");
  EXPECT_EQ(f.doubles("/time").size(), 31u);
  EXPECT_EQ(f.string_attribute("/", "status"), "completed");
}

// A step that does not converge even after cuts is published with converged = false and the last
// accepted state, and ends the server with exit status 2; the run file keeps the accepted steps.
TEST_F(SimServer, UnconvergedStepIsPublishedAndStopsTheServer) {
  std::string text = kBoxScene;
  text += "solver: {max_iterations: 1}\n";
  text.replace(text.find("dt: 0.002}"), 10, "dt: 0.002, max_cuts: 0}");
  write("scene.yaml", text);
  url_ = bus_url(7714);
  controller_ = std::make_unique<ServerController>(url_);
  server_ = std::make_unique<ChildProcess>(
      SIM_SERVER_PATH,
      std::vector<std::string>{(dir_ / "scene.yaml").string(), "--lcm-url", url_, "--output",
                               (dir_ / "run.h5").string()},
      dir_);
  const auto s0 = controller_->wait_step(0);
  ASSERT_TRUE(s0) << server_->stderr_text();
  controller_->send_activation(1, {"flexor"}, {0.5});
  const auto failed =
      controller_->wait_state([](const lcmt_tongue_state& s) { return !s.converged; });
  ASSERT_TRUE(failed) << server_->stderr_text();
  EXPECT_EQ(failed->step, 0);
  EXPECT_EQ(failed->positions, s0->positions);
  EXPECT_NE(failed->status.find("step 1 failed to converge"), std::string::npos) << failed->status;
  EXPECT_EQ(server_->wait_exit(kExitWaitMs), 2);
  const RunFile f(dir_ / "run.h5");
  EXPECT_EQ(f.doubles("/time").size(), 1u);
  EXPECT_EQ(f.string_attribute("/", "status").rfind("failed: step 1 failed to converge", 0), 0u);
}

TEST_F(SimServer, SceneWithoutMusclesIsAClearError) {
  std::string text = kBoxScene;
  text.erase(text.find("muscles:"), text.find("damping:") - text.find("muscles:"));
  const testing::RunResult r = testing::run_command(
      SIM_SERVER_PATH, "'" + write("scene.yaml", text) + "' --lcm-url '" + bus_url(7713) + "'",
      dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("the server needs muscles"), std::string::npos) << r.err;
}

// Real-time mode paces the steps to the wall clock: step n + 1 starts no earlier than
// start + n dt, so 41 steps of 2 ms span at least 40 dt between the states of steps 0 and 41
// (both stamped by the server's clock); an activation tagged -1 is held.
TEST_F(SimServer, RealTimeIsPacedToTheWallClockAndHoldsTheActivation) {
  start(7740, {"--mode", "realtime", "--max-steps", "41"});
  const auto s0 = controller_->wait_step(0);
  ASSERT_TRUE(s0) << server_->stderr_text();
  controller_->send_activation(-1, {"flexor"}, {0.6});
  const auto held = controller_->wait_state(
      [](const lcmt_tongue_state& s) { return s.activations == std::vector<double>{0.6}; });
  ASSERT_TRUE(held) << server_->stderr_text();
  const auto last = controller_->wait_step(41);
  ASSERT_TRUE(last) << server_->stderr_text();
  EXPECT_EQ(last->activations, (std::vector<double>{0.6}));
  EXPECT_GE(last->utime - s0->utime, static_cast<std::int64_t>(40 * kDt * 1e6));
  EXPECT_EQ(server_->wait_exit(kExitWaitMs), 0) << server_->stderr_text();
  const RunFile f(dir_ / "run.h5");
  EXPECT_EQ(f.doubles("/time").size(), 42u);
  EXPECT_EQ(f.string_attribute("/", "status"), "completed");
}

// A dt no machine can keep up with: every late step is an overrun, counted in the state.
TEST_F(SimServer, RealTimeCountsOverruns) {
  std::string text = kBoxScene;
  text.replace(text.find("dt: 0.002}"), 10, "dt: 0.000001}");
  write("scene.yaml", text);
  url_ = bus_url(7741);
  controller_ = std::make_unique<ServerController>(url_);
  server_ = std::make_unique<ChildProcess>(
      SIM_SERVER_PATH,
      std::vector<std::string>{(dir_ / "scene.yaml").string(), "--lcm-url", url_, "--mode",
                               "realtime", "--max-steps", "20"},
      dir_);
  const auto s0 = controller_->wait_step(0);
  ASSERT_TRUE(s0) << server_->stderr_text();
  EXPECT_EQ(s0->overruns, 0);
  const auto last = controller_->wait_step(20);
  ASSERT_TRUE(last) << server_->stderr_text();
  EXPECT_GT(last->overruns, 0);
  EXPECT_LE(last->overruns, 20);
  EXPECT_EQ(server_->wait_exit(kExitWaitMs), 0) << server_->stderr_text();
  EXPECT_NE(server_->stderr_text().find("overrun"), std::string::npos) << server_->stderr_text();
}

std::size_t count_of(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// --on-silence decay: after --silence-s without a valid activation all levels go to 0, said once
// on stderr however long the silence lasts.
TEST_F(SimServer, RealTimeDecaysToZeroAfterSilence) {
  start(7742, {"--mode", "realtime", "--silence-s", "0.1", "--on-silence", "decay"});
  ASSERT_TRUE(controller_->wait_step(0)) << server_->stderr_text();
  const auto sent = std::chrono::steady_clock::now();
  controller_->send_activation(-1, {"flexor"}, {0.8});
  const auto held = controller_->wait_state(
      [](const lcmt_tongue_state& s) { return s.activations == std::vector<double>{0.8}; });
  ASSERT_TRUE(held) << server_->stderr_text();
  const auto decayed = controller_->wait_state(
      [](const lcmt_tongue_state& s) { return s.activations == std::vector<double>{0.0}; });
  ASSERT_TRUE(decayed) << server_->stderr_text();
  EXPECT_GE(std::chrono::steady_clock::now() - sent, std::chrono::milliseconds(100));
  EXPECT_GT(decayed->step, held->step);
  // Still silent 100 steps (0.2 s) later: still 0, reported once.
  const auto later = controller_->wait_step(decayed->step + 100);
  ASSERT_TRUE(later) << server_->stderr_text();
  EXPECT_EQ(later->activations, (std::vector<double>{0.0}));
  EXPECT_EQ(shut_down(), 0) << server_->stderr_text();
  EXPECT_EQ(count_of(server_->stderr_text(), "no activation for 0.1 s"), 1u)
      << server_->stderr_text();
  EXPECT_NE(server_->stderr_text().find("activations set to 0"), std::string::npos)
      << server_->stderr_text();
}

TEST_F(SimServer, RealTimeSilenceStopsTheServerWhenAskedTo) {
  start(7743, {"--mode", "realtime", "--silence-s", "0.1", "--on-silence", "stop"});
  ASSERT_TRUE(controller_->wait_step(0)) << server_->stderr_text();
  EXPECT_EQ(server_->wait_exit(kExitWaitMs), 3) << server_->stderr_text();
  const RunFile f(dir_ / "run.h5");
  EXPECT_EQ(f.string_attribute("/", "status"), "stopped: no activation for 0.1 s");
}

// A 40 x 20 x 20 mm block, 4 x 2 x 2 elements: 45 nodes, of which the 3 on the inner axis are not
// on the surface.
TEST_F(SimServer, SurfaceNodesOnly) {
  std::string text = kBoxScene;
  text.replace(text.find("size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]"), 46,
               "size: [0.04, 0.02, 0.02], divisions: [4, 2, 2]");
  write("scene.yaml", text);
  url_ = bus_url(7744);
  controller_ = std::make_unique<ServerController>(url_);
  server_ = std::make_unique<ChildProcess>(
      SIM_SERVER_PATH,
      std::vector<std::string>{(dir_ / "scene.yaml").string(), "--lcm-url", url_, "--output",
                               (dir_ / "run.h5").string(), "--nodes", "surface"},
      dir_);
  const auto model = controller_->wait_model();
  ASSERT_TRUE(model) << server_->stderr_text();
  ASSERT_EQ(model->num_nodes, 45);
  // Surface nodes, found from the rest positions: some coordinate at the box's min or max.
  const std::vector<double>& rest = model->rest_positions;
  std::vector<std::int32_t> surface;
  for (int i = 0; i < model->num_nodes; ++i) {
    bool on = false;
    for (int c = 0; c < 3; ++c) {
      double lo = rest[c], hi = rest[c];
      for (int j = 0; j < model->num_nodes; ++j) {
        lo = std::min(lo, rest[3 * j + c]);
        hi = std::max(hi, rest[3 * j + c]);
      }
      on = on || std::abs(rest[3 * i + c] - lo) < 1e-12 || std::abs(rest[3 * i + c] - hi) < 1e-12;
    }
    if (on) surface.push_back(i);
  }
  ASSERT_EQ(surface.size(), 42u);
  const auto s0 = controller_->wait_step(0);
  ASSERT_TRUE(s0) << server_->stderr_text();
  EXPECT_EQ(s0->num_nodes, 42);
  EXPECT_EQ(s0->node_indices, surface);
  ASSERT_EQ(s0->num_positions, 3 * 42);
  ASSERT_EQ(s0->positions.size(), 3u * 42u);
  for (std::size_t k = 0; k < surface.size(); ++k)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(s0->positions[3 * k + c], rest[3 * surface[k] + c]);  // not settled: at rest
  const lcmt_tongue_state s1 = step_to(1, 0.5);
  EXPECT_EQ(s1.node_indices, surface);
  EXPECT_EQ(s1.positions.size(), 3u * 42u);
  EXPECT_EQ(shut_down(), 0) << server_->stderr_text();
  const RunFile f(dir_ / "run.h5");
  EXPECT_EQ(f.doubles("/positions").size(), 2u * 45u * 3u);  // the run file keeps all nodes
}

TEST_F(SimServer, NodeSetsTheMeshLacksAreAClearError) {
  const std::string scene = write("scene.yaml", kBoxScene);
  for (const std::string subset : {"midsagittal", "landmarks"}) {
    const testing::RunResult r = testing::run_command(
        SIM_SERVER_PATH, "'" + scene + "' --nodes " + subset + " --lcm-url '" + bus_url(7745) + "'",
        dir_);
    EXPECT_EQ(r.exit_code, 1) << subset;
    EXPECT_NE(r.err.find("the mesh has no"), std::string::npos) << r.err;
  }
}

TEST_F(SimServer, PublishEveryKStepsInFastMode) {
  start(7746, {"--mode", "fast", "--max-steps", "23", "--publish-every", "5"});
  std::vector<std::int64_t> steps;
  ASSERT_TRUE(controller_->wait_state([&steps](const lcmt_tongue_state& s) {
    steps.push_back(s.step);
    return s.step >= 23;
  })) << server_->stderr_text();
  EXPECT_EQ(steps, (std::vector<std::int64_t>{0, 5, 10, 15, 20, 23}));  // and the last step
  EXPECT_EQ(server_->wait_exit(kExitWaitMs), 0) << server_->stderr_text();
  const RunFile f(dir_ / "run.h5");
  EXPECT_EQ(f.doubles("/time").size(), 24u);  // every step logged
}

TEST_F(SimServer, PublishEveryIsNotForLockStep) {
  const testing::RunResult r =
      testing::run_command(SIM_SERVER_PATH,
                           "'" + write("scene.yaml", kBoxScene) +
                               "' --publish-every 2 --lcm-url '" + bus_url(7747) + "'",
                           dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--publish-every applies to --mode fast and realtime only"),
            std::string::npos)
      << r.err;
}

TEST_F(SimServer, RepeatsAreForLockStepAndBounded) {
  const std::string scene = write("scene.yaml", kBoxScene), url = bus_url(7748);
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--mode fast --repeat-ms 20", "--repeat-ms and --repeats apply to --mode lockstep only"},
      {"--mode realtime --repeats 3", "--repeat-ms and --repeats apply to --mode lockstep only"},
      {"--repeat-ms -1", "--repeat-ms must be an integer in [0, 60000] ms"},
      {"--repeats 21", "--repeats must be an integer in [0, 20]"}};
  for (const auto& [options, message] : cases) {
    const testing::RunResult r = testing::run_command(
        SIM_SERVER_PATH, "'" + scene + "' " + options + " --lcm-url '" + url + "'", dir_);
    EXPECT_EQ(r.exit_code, 1) << options;
    EXPECT_NE(r.err.find(message), std::string::npos) << options << ": " << r.err;
  }
}

}  // namespace
}  // namespace tongue::server
