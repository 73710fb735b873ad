// The Java controller (controllers/java/StepController.java, through the build's wrapper; the
// MATLAB controller is it line for line) drives the real sim_server over udpm; its runs equal bit
// for bit those of the C++ test driver sending the same activations and those of sim_batch
// running the same schedule. Ports 7980-7984.
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
#ifndef JAVA_STEP_CONTROLLER_PATH
#error "JAVA_STEP_CONTROLLER_PATH must name the Java controller's wrapper"
#endif

namespace tongue::controller {
namespace {

using testing::bus_url;
using testing::ChildProcess;
using testing::logged;
using testing::Schedule;
constexpr int kSteps = testing::kControllerSteps;
constexpr int kRunWaitMs = 60000;  // a whole run of 12 box steps, JVM start-up included

class JavaController : public testing::StepControllerTest {
 protected:
  JavaController() : StepControllerTest(JAVA_STEP_CONTROLLER_PATH, kRunWaitMs, "20000") {}
  std::unique_ptr<ChildProcess> start_java(const std::string& url, const std::string& name,
                                           const std::vector<std::string>& args) {
    return start_controller(url, name, args);
  }
};

// The schedule of LuaController.DrivesTheServerAsTheCppDriverDoes, so that the Java run is the
// Lua run too. One port for both runs, one after the other: the Java run's server has exited
// before the C++ driver subscribes, and nothing else is on the port.
TEST_F(JavaController, DrivesTheServerAsTheCppDriverDoes) {
  write("scene.yaml", testing::kBoxScene);
  // dt = 2 ms; step k + 1 starts at t = 2k ms. flexor=0.3@0:0.01 holds for the steps starting at
  // 0 .. 8 ms (1-5), flexor=0.8@0.006:0.016 for those at 6 .. 14 ms (4-8) and, being later on
  // the command line, wins where both hold; 0 from step 9 on.
  const Schedule flexor{0.3, 0.3, 0.3, 0.8, 0.8, 0.8, 0.8, 0.8, 0.0, 0.0, 0.0, 0.0};
  const int port = 7980;
  {
    const std::string url = bus_url(port);
    auto java = start_java(
        url, "java",
        {"--max-steps", std::to_string(kSteps), "flexor=0.3@0:0.01", "flexor=0.8@0.006:0.016"});
    auto server = start_server(url, "java_run");
    ASSERT_EQ(server->wait_exit(kRunWaitMs), 0) << server->stderr_text();
    ASSERT_EQ(java->wait_exit(kRunWaitMs), 0) << java->stderr_text();
    EXPECT_NE(java->stderr_text().find("answered 12 states; reached step 12 (t = 0.024 s)"),
              std::string::npos)
        << java->stderr_text();
  }
  run_cpp_driver(port, {"flexor"}, {flexor});
  testing::expect_same_results(dir_ / "java_run.h5", dir_ / "cpp.h5", kSteps + 1);
  const testing::RunFile run(dir_ / "java_run.h5");
  EXPECT_EQ(run.doubles("/activations"), logged({flexor}));
}

// Started after the server (which published its model long before), a controller asks for the
// model ("describe"): one naming a muscle the model lacks then ends with status 1, and one
// started after it drives the waiting server from step 0, as sim_batch runs the same schedule
// (sim_batch's step to t uses the levels at t, active while start <= t <= end: steps 1-5 for
// [0, 0.01] s; the controller's window [0, 0.01) s holds for the steps starting at 0 .. 8 ms:
// steps 1-5).
TEST_F(JavaController, StartedAfterTheServerItAsksForTheModel) {
  std::string scene = testing::kBoxScene;
  scene += "activations:\n  - {muscles: [flexor], level: 0.5, start: 0.0, end: 0.01}\n";
  write("scene.yaml", scene);
  ASSERT_NO_FATAL_FAILURE(run_sim_batch());
  const int steps = 10;  // the scene's duration, 0.02 s, for sim_batch
  const std::string url = bus_url(7982);
  auto server = start_server(url, "java_run", steps);
  // The server reports its wait for step 1 after its timeout (1 s): the model is long gone.
  ASSERT_TRUE(server->wait_stderr("activation for step 1", kRunWaitMs)) << server->stderr_text();
  auto lacking = start_java(url, "lacking", {"styloglossus=0.5"});
  EXPECT_EQ(lacking->wait_exit(kRunWaitMs), 1) << lacking->stderr_text();
  EXPECT_NE(lacking->stderr_text().find("muscle 'styloglossus' is not in the model (its "
                                        "muscles: flexor)"),
            std::string::npos)
      << lacking->stderr_text();
  auto java = start_java(url, "java", {"--max-steps", std::to_string(steps), "flexor=0.5@0:0.01"});
  ASSERT_EQ(java->wait_exit(kRunWaitMs), 0) << java->stderr_text();
  EXPECT_NE(java->stderr_text().find("answered 10 states; reached step 10"), std::string::npos)
      << java->stderr_text();
  ASSERT_EQ(server->wait_exit(kRunWaitMs), 0) << server->stderr_text();
  testing::expect_same_results(dir_ / "java_run.h5", dir_ / "batch.h5", steps + 1,
                               testing::run_state_datasets());
}

// Two Java controllers naming the same muscle with --controllers 2: the second message for
// step 1 is rejected, and its sender reads the server's rejection notice and exits 5 with the
// reason (the other is left waiting; the server stops by its silence rule).
TEST_F(JavaController, TheOneRejectedForAnOverlapIsToldWhy) {
  write("scene.yaml", testing::kTwoMuscleBoxScene);
  const std::string url = bus_url(7981);
  auto first = start_java(url, "first", {"flexor=0.5"});
  auto second = start_java(url, "second", {"flexor=0.7"});
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
// from the scene's schedule and by sim_server under the Java controller: the same positions, bit
// for bit (as LuaController.ReproducesSimBatchOnTheTongue).
TEST_F(JavaController, ReproducesSimBatchOnTheTongue) {
  std::string scene = testing::read_text(SCENES_DIR "/tongue_sg_3n.yaml");
  const std::string duration = "duration: 0.12 ";
  ASSERT_NE(scene.find(duration), std::string::npos);
  scene.replace(scene.find(duration), duration.size(), "duration: 0.02 ");
  write("scene.yaml", scene);
  ASSERT_NO_FATAL_FAILURE(run_sim_batch());
  {
    const std::string url = bus_url(7983);
    auto java = start_java(url, "java",
                           {"--max-steps", "5", "SG_left=0.125@0:0.12", "SG_right=0.125@0:0.12"});
    auto server = start_server(url, "java_run", 5);
    ASSERT_EQ(server->wait_exit(120000), 0) << server->stderr_text();
    ASSERT_EQ(java->wait_exit(kRunWaitMs), 0) << java->stderr_text();
  }
  testing::expect_same_results(dir_ / "java_run.h5", dir_ / "batch.h5", 6,
                               testing::run_state_datasets());
}

// No server: the controller asks for the model, then gives up with the timeout's status, 4.
TEST_F(JavaController, NoServerIsATimeout) {
  const testing::RunResult r =
      testing::run_command(JAVA_STEP_CONTROLLER_PATH,
                           "--lcm-url '" + bus_url(7984) + "' --timeout-ms 2000 flexor=1", dir_);
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find("step_controller: nothing from the server on TONGUE_* for 2000 ms while "
                       "waiting for the model"),
            std::string::npos)
      << r.err;
}

TEST_F(JavaController, BadCommandLinesExitWithStatus1) {
  for (const std::string args :
       {"", "flexor", "flexor=1.5", "flexor=0.5@0.02:0.01", "flexor=0.5@-1", "flexor=0x1",
        "--max-steps 0 a=1", "--max-steps 1.5 a=1", "--prefix lower_ a=1", "--frobnicate a=1",
        "--timeout-ms"}) {
    const testing::RunResult r = testing::run_command(JAVA_STEP_CONTROLLER_PATH, args, dir_);
    EXPECT_EQ(r.exit_code, 1) << "'" << args << "': " << r.err;
    EXPECT_NE(r.err.find("usage: step_controller"), std::string::npos) << r.err;
  }
  const testing::RunResult help = testing::run_command(JAVA_STEP_CONTROLLER_PATH, "--help", dir_);
  EXPECT_EQ(help.exit_code, 0) << help.err;
  EXPECT_NE(help.out.find("usage: step_controller"), std::string::npos) << help.out;
}

}  // namespace
}  // namespace tongue::controller
