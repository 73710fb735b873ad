// The Lua controller (controllers/lua/step_controller.lua, through the build's wrapper) drives the
// real sim_server over udpm; its runs equal bit for bit those of the C++ test driver sending the
// same activations, which the test spells out step by step from the command line's windows.
// Ports 7850-7855.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "support/run_command.hpp"
#include "support/run_file.hpp"
#include "support/same_run.hpp"
#include "support/step_controller_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif
#ifndef SIM_BATCH_PATH
#error "SIM_BATCH_PATH must name the sim_batch executable"
#endif
#ifndef SCENES_DIR
#error "SCENES_DIR must name the project's scenes folder"
#endif
#ifndef LUA_STEP_CONTROLLER_PATH
#error "LUA_STEP_CONTROLLER_PATH must name the Lua controller's wrapper"
#endif

namespace tongue::controller {
namespace {

using testing::bus_url;
using testing::ChildProcess;
using testing::logged;
using testing::Schedule;
using testing::ServerController;
constexpr int kSteps = testing::kControllerSteps;
constexpr int kRunWaitMs = 20000;  // a whole run of 12 box steps, Lua start-up included

class LuaController : public testing::StepControllerTest {
 protected:
  LuaController() : StepControllerTest(LUA_STEP_CONTROLLER_PATH, kRunWaitMs, "10000") {}
  std::unique_ptr<ChildProcess> start_lua(const std::string& url, const std::string& name,
                                          const std::vector<std::string>& args) {
    return start_controller(url, name, args);
  }
};

TEST_F(LuaController, DrivesTheServerAsTheCppDriverDoes) {
  write("scene.yaml", testing::kBoxScene);
  // dt = 2 ms; step k + 1 starts at t = 2k ms. flexor=0.3@0:0.01 holds for the steps starting at
  // 0 .. 8 ms (1-5), flexor=0.8@0.006:0.016 for those at 6 .. 14 ms (4-8) and, being later on
  // the command line, wins where both hold; 0 from step 9 on.
  const Schedule flexor{0.3, 0.3, 0.3, 0.8, 0.8, 0.8, 0.8, 0.8, 0.0, 0.0, 0.0, 0.0};
  {
    const std::string url = bus_url(7850);
    auto lua = start_lua(
        url, "lua",
        {"--max-steps", std::to_string(kSteps), "flexor=0.3@0:0.01", "flexor=0.8@0.006:0.016"});
    auto server = start_server(url, "lua_run");
    ASSERT_EQ(server->wait_exit(kRunWaitMs), 0) << server->stderr_text();
    ASSERT_EQ(lua->wait_exit(kRunWaitMs), 0) << lua->stderr_text();
    EXPECT_NE(lua->stderr_text().find("answered 12 states; reached step 12"), std::string::npos)
        << lua->stderr_text();
  }
  run_cpp_driver(7851, {"flexor"}, {flexor});
  testing::expect_same_results(dir_ / "lua_run.h5", dir_ / "cpp.h5", kSteps + 1);
  const testing::RunFile run(dir_ / "lua_run.h5");
  EXPECT_EQ(run.doubles("/activations"), logged({flexor}));
}

// Two Lua controllers, one per muscle, with --controllers 2, equal one C++ controller sending
// both muscles' levels in one message.
TEST_F(LuaController, TwoInstancesOnePerMuscleWithTwoControllers) {
  write("scene.yaml", testing::kTwoMuscleBoxScene);
  // flexor=0.6@0.004:0.014: steps starting at 4 .. 12 ms (3-7). extensor=0.4@0:0.008: steps at
  // 0 .. 6 ms (1-4); extensor=1@0.016: from 16 ms on (9-12).
  const Schedule flexor{0.0, 0.0, 0.6, 0.6, 0.6, 0.6, 0.6, 0.0, 0.0, 0.0, 0.0, 0.0};
  const Schedule extensor{0.4, 0.4, 0.4, 0.4, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0};
  {
    const std::string url = bus_url(7852);
    const std::string steps = std::to_string(kSteps);
    auto lua_flexor =
        start_lua(url, "lua_flexor", {"--max-steps", steps, "flexor=0.6@0.004:0.014"});
    auto lua_extensor = start_lua(
        url, "lua_extensor", {"--max-steps", steps, "extensor=0.4@0:0.008", "extensor=1@0.016"});
    auto server = start_server(url, "lua_run", kSteps, {"--controllers", "2"});
    ASSERT_EQ(server->wait_exit(kRunWaitMs), 0) << server->stderr_text();
    ASSERT_EQ(lua_flexor->wait_exit(kRunWaitMs), 0) << lua_flexor->stderr_text();
    ASSERT_EQ(lua_extensor->wait_exit(kRunWaitMs), 0) << lua_extensor->stderr_text();
  }
  run_cpp_driver(7853, {"flexor", "extensor"}, {flexor, extensor});
  testing::expect_same_results(dir_ / "lua_run.h5", dir_ / "cpp.h5", kSteps + 1);
  const testing::RunFile run(dir_ / "lua_run.h5");
  EXPECT_EQ(run.doubles("/activations"), logged({flexor, extensor}));
}

// Two Lua controllers naming the same muscle with --controllers 2 (port 7907): the second
// message for step 1 is rejected, and its sender reads the server's rejection notice and exits
// 5 with the reason (the other is left waiting; the server stops by its silence rule).
TEST_F(LuaController, TheOneRejectedForAnOverlapIsToldWhy) {
  write("scene.yaml", testing::kTwoMuscleBoxScene);
  const std::string url = bus_url(7907);
  auto first = start_lua(url, "first", {"flexor=0.5"});
  auto second = start_lua(url, "second", {"flexor=0.7"});
  auto server = start_server(
      url, "run", kSteps, {"--controllers", "2", "--timeout-ms", "3000", "--on-silence", "stop"});
  EXPECT_EQ(server->wait_exit(kRunWaitMs), 3) << server->stderr_text();
  // The rejected one has said so by now; the other waits until its own timeout.
  const std::string told = "the server rejected its activation for step 1";
  ChildProcess& rejected = first->stderr_text().find(told) != std::string::npos ? *first : *second;
  ASSERT_EQ(rejected.wait_exit(kRunWaitMs), 5) << first->stderr_text() << second->stderr_text();
  EXPECT_NE(rejected.stderr_text().find(told + " (step_controller:"), std::string::npos)
      << rejected.stderr_text();
  EXPECT_NE(rejected.stderr_text().find("overlapping activation: \"flexor\" is already set"),
            std::string::npos)
      << rejected.stderr_text();
}

// On the built-in tongue: the paper's styloglossus experiment (scenes/tongue_sg_3n.yaml, settled,
// SG at 3 N = level 3 / 24 of both halves from t = 0), cut to 5 steps of 4 ms, run by sim_batch
// from the scene's schedule and by sim_server under the Lua controller: the same positions, bit
// for bit (sim_batch's step to t uses the levels at t, active while start <= t <= end: steps 1-5;
// the controller's window [0, 0.12) s holds for the steps starting at 0 .. 16 ms: steps 1-5).
TEST_F(LuaController, ReproducesSimBatchOnTheTongue) {
  std::string scene = testing::read_text(SCENES_DIR "/tongue_sg_3n.yaml");
  const std::string duration = "duration: 0.12 ";
  ASSERT_NE(scene.find(duration), std::string::npos);
  scene.replace(scene.find(duration), duration.size(), "duration: 0.02 ");
  write("scene.yaml", scene);
  ASSERT_NO_FATAL_FAILURE(run_sim_batch());
  {
    const std::string url = bus_url(7855);
    auto lua = start_lua(url, "lua",
                         {"--max-steps", "5", "SG_left=0.125@0:0.12", "SG_right=0.125@0:0.12"});
    std::vector<std::string> args{(dir_ / "scene.yaml").string(), "--lcm-url",   url, "--output",
                                  (dir_ / "lua_run.h5").string(), "--max-steps", "5"};
    ChildProcess server(SIM_SERVER_PATH, args, dir_, "server");
    ASSERT_EQ(server.wait_exit(60000), 0) << server.stderr_text();
    ASSERT_EQ(lua->wait_exit(kRunWaitMs), 0) << lua->stderr_text();
  }
  testing::expect_same_results(dir_ / "lua_run.h5", dir_ / "batch.h5", 6,
                               testing::run_state_datasets());
}

TEST_F(LuaController, AMuscleTheModelLacksIsAClearError) {
  write("scene.yaml", testing::kBoxScene);
  const std::string url = bus_url(7854);
  ServerController controller(url);
  ASSERT_TRUE(controller.good());
  auto lua = start_lua(url, "lua", {"styloglossus=0.5"});
  auto server = start_server(url, "run");
  EXPECT_EQ(lua->wait_exit(kRunWaitMs), 1) << lua->stderr_text();
  EXPECT_NE(lua->stderr_text().find("muscle 'styloglossus' is not in the model (its muscles: "
                                    "flexor)"),
            std::string::npos)
      << lua->stderr_text();
  controller.send_command("shutdown");
  EXPECT_EQ(server->wait_exit(kRunWaitMs), 0) << server->stderr_text();
}

TEST_F(LuaController, BadCommandLinesExitWithStatus1) {
  for (const std::string args :
       {"", "flexor", "flexor=1.5", "flexor=0.5@0.02:0.01", "flexor=0.5@-1", "--max-steps 0 a=1",
        "--prefix lower_ a=1", "--frobnicate a=1"}) {
    const testing::RunResult r = testing::run_command(LUA_STEP_CONTROLLER_PATH, args, dir_);
    EXPECT_EQ(r.exit_code, 1) << "'" << args << "': " << r.err;
    EXPECT_NE(r.err.find("usage: step_controller.lua"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace tongue::controller
