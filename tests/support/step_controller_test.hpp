#pragma once
// What the tests of the step controllers written in other languages (Lua, Java) share: one
// started through its build-tree wrapper and waited for until it listens, sim_server on the
// test's scene, the C++ driver's reference run of the same levels, sim_batch's run of the scene,
// and the activations such a run logs. The test target defines SIM_SERVER_PATH and
// SIM_BATCH_PATH.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "support/run_command.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::testing {

inline constexpr int kControllerSteps = 12;  // of the box scenes' runs
using Schedule = std::vector<double>;        // a muscle's level for steps 1 .. kControllerSteps

// The logged activations of a run of these schedules: frame 0 all 0, frame k the levels of step k.
inline std::vector<double> logged(const std::vector<Schedule>& schedules) {
  std::vector<double> out(schedules.size(), 0.0);
  for (int k = 0; k < kControllerSteps; ++k)
    for (const Schedule& s : schedules) out.push_back(s[k]);
  return out;
}

class StepControllerTest : public TempDirTest {
 protected:
  // wrapper: the controller's build-tree wrapper; run_wait_ms: how long a whole run may take,
  // its start-up included; timeout_ms: the controller's own --timeout-ms.
  StepControllerTest(std::string wrapper, int run_wait_ms, std::string timeout_ms)
      : wrapper_(std::move(wrapper)),
        run_wait_ms_(run_wait_ms),
        timeout_ms_(std::move(timeout_ms)) {}

  // Starts one controller (args after the bus options) and waits until it listens, so that a
  // server started next cannot publish anything before it is subscribed.
  std::unique_ptr<ChildProcess> start_controller(const std::string& url, const std::string& name,
                                                 const std::vector<std::string>& args) {
    std::vector<std::string> all{"--lcm-url", url, "--timeout-ms", timeout_ms_};
    all.insert(all.end(), args.begin(), args.end());
    auto controller = std::make_unique<ChildProcess>(wrapper_, all, dir_, name);
    EXPECT_TRUE(controller->started());
    EXPECT_TRUE(controller->wait_stderr("listening on", run_wait_ms_)) << controller->stderr_text();
    return controller;
  }

  // sim_server on dir_/scene.yaml into dir_/<run>.h5 for `steps` steps.
  std::unique_ptr<ChildProcess> start_server(const std::string& url, const std::string& run,
                                             int steps = kControllerSteps,
                                             const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args{(dir_ / "scene.yaml").string(),
                                  "--lcm-url",
                                  url,
                                  "--output",
                                  (dir_ / (run + ".h5")).string(),
                                  "--max-steps",
                                  std::to_string(steps)};
    args.insert(args.end(), extra.begin(), extra.end());
    auto server = std::make_unique<ChildProcess>(SIM_SERVER_PATH, args, dir_, run);
    EXPECT_TRUE(server->started());
    return server;
  }

  // The C++ driver's run into dir_/cpp.h5: one controller sending, for every step, the levels
  // of the schedules.
  void run_cpp_driver(int port, const std::vector<std::string>& muscles,
                      const std::vector<Schedule>& schedules) {
    const std::string url = bus_url(port);
    ServerController controller(url);
    ASSERT_TRUE(controller.good());
    auto server = start_server(url, "cpp");
    for (int k = 0; k < kControllerSteps; ++k) {
      ASSERT_TRUE(controller.wait_step(k, run_wait_ms_)) << server->stderr_text();
      std::vector<double> levels;
      for (const Schedule& s : schedules) levels.push_back(s[k]);
      controller.send_activation(k + 1, muscles, levels);
    }
    ASSERT_EQ(server->wait_exit(run_wait_ms_), 0) << server->stderr_text();
  }

  // sim_batch's run of dir_/scene.yaml into dir_/batch.h5.
  void run_sim_batch() {
    const RunResult batch =
        run_command(SIM_BATCH_PATH,
                    "'" + (dir_ / "scene.yaml").string() + "' --quiet --output '" +
                        (dir_ / "batch.h5").string() + "'",
                    dir_);
    ASSERT_EQ(batch.exit_code, 0) << batch.err;
  }

  const std::string wrapper_;
  const int run_wait_ms_;
  const std::string timeout_ms_;
};

}  // namespace tongue::testing
