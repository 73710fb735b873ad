// Lock-step with several controllers (sim_server --controllers N), end to end: the real sim_server
// on a real LCM bus (udpm on the loopback, ports 7830-7836, one per run), each controller with its
// own LCM instance. The two-muscle box: controller 1 drives "flexor", controller 2 "extensor".
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "support/run_command.hpp"
#include "support/run_file.hpp"
#include "support/same_run.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif

namespace tongue::server {
namespace {

namespace fs = std::filesystem;
using testing::bus_url;
using testing::ChildProcess;
using testing::ServerController;
using tongue_lcm::lcmt_tongue_state;

constexpr int kExitWaitMs = 5000;
constexpr int kSteps = 12;

// Controller 1's level of flexor for step k (varies every step).
double flexor_level(int k) {
  return 0.05 + 0.1 * (k % 4);
}
// Controller 2 names extensor on the steps where this is set; on the others it sends a message
// naming no muscle, so extensor keeps the level it had.
std::optional<double> extensor_level(int k) {
  if (k % 3 == 0) return std::nullopt;
  return k < 6 ? 0.2 : 0.7;
}

class MultiController : public testing::TempDirTest {
 protected:
  std::unique_ptr<ChildProcess> start_server(const std::string& url, const std::string& name,
                                             const std::vector<std::string>& extra) {
    std::vector<std::string> args{(dir_ / "scene.yaml").string(), "--lcm-url", url, "--output",
                                  (dir_ / (name + ".h5")).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    auto server = std::make_unique<ChildProcess>(SIM_SERVER_PATH, args, dir_, name);
    EXPECT_TRUE(server->started());
    return server;
  }
  void SetUp() override {
    TempDirTest::SetUp();
    write("scene.yaml", testing::kTwoMuscleBoxScene);
  }
};

// One lock-step controller: answers the states of steps 0 .. steps - 1 with the message send
// makes for step k + 1, then waits for the state of the last step. Returns what went wrong, or
// an empty text. Runs in its own thread, on its own LCM instance.
std::string drive(ServerController& controller, int steps,
                  const std::function<void(ServerController&, int)>& send) {
  for (int k = 0; k < steps; ++k) {
    if (!controller.wait_step(k)) return "no state for step " + std::to_string(k);
    send(controller, k + 1);
  }
  if (!controller.wait_step(steps)) return "no state for step " + std::to_string(steps);
  return "";
}

void send_flexor(ServerController& c, int k) {
  c.send_activation(k, {"flexor"}, {flexor_level(k)});
}
void send_extensor(ServerController& c, int k) {
  const std::optional<double> level = extensor_level(k);
  if (level) {
    c.send_activation(k, {"extensor"}, {*level});
  } else {
    c.send_activation(k, {}, {});
  }
}

// Two controllers, each driving its own muscle from its own thread, reach bit for bit the run of
// one controller sending the merged activation; the logged activations are the merged schedule.
TEST_F(MultiController, TwoControllersEqualOneSendingTheMergedActivation) {
  {
    const std::string url = bus_url(7830);
    ServerController first(url), second(url);
    ASSERT_TRUE(first.good() && second.good());
    auto server = start_server(url, "two", {"--controllers", "2"});
    std::string error1, error2;
    std::thread t1([&] { error1 = drive(first, kSteps, send_flexor); });
    std::thread t2([&] { error2 = drive(second, kSteps, send_extensor); });
    t1.join();
    t2.join();
    ASSERT_EQ(error1, "") << server->stderr_text();
    ASSERT_EQ(error2, "") << server->stderr_text();
    first.send_command("shutdown");
    ASSERT_EQ(server->wait_exit(kExitWaitMs), 0) << server->stderr_text();
    EXPECT_NE(server->stderr_text().find("lock-step mode (2 controllers)"), std::string::npos)
        << server->stderr_text();
  }
  {
    const std::string url = bus_url(7831);
    ServerController controller(url);
    ASSERT_TRUE(controller.good());
    auto server = start_server(url, "one", {});
    const std::string error = drive(controller, kSteps, [](ServerController& c, int k) {
      const std::optional<double> extensor = extensor_level(k);
      if (extensor) {
        c.send_activation(k, {"flexor", "extensor"}, {flexor_level(k), *extensor});
      } else {
        c.send_activation(k, {"flexor"}, {flexor_level(k)});
      }
    });
    ASSERT_EQ(error, "") << server->stderr_text();
    controller.send_command("shutdown");
    ASSERT_EQ(server->wait_exit(kExitWaitMs), 0) << server->stderr_text();
  }
  testing::expect_same_results(dir_ / "two.h5", dir_ / "one.h5", kSteps + 1);

  // The schedule, merged by hand: frame k holds the levels used during step k (frame 0: all 0).
  std::vector<double> expected{0.0, 0.0};
  double extensor = 0.0;
  for (int k = 1; k <= kSteps; ++k) {
    extensor = extensor_level(k).value_or(extensor);
    expected.push_back(flexor_level(k));
    expected.push_back(extensor);
  }
  const testing::RunFile run(dir_ / "two.h5");
  EXPECT_EQ(run.doubles("/activations"), expected);
  EXPECT_EQ(run.strings("/muscles/names"), (std::vector<std::string>{"flexor", "extensor"}));
  const std::vector<double> positions = run.doubles("/positions");
  EXPECT_NE(std::vector<double>(positions.begin(), positions.begin() + 60),
            std::vector<double>(positions.end() - 60, positions.end()));  // the muscles moved it
}

// A message naming a muscle that an earlier message already set for the same step is rejected
// whole and counted; the step is then made by a valid second message, with the first message's
// level kept. The pauses make the order deterministic: a paused state is published only after
// every message sent before the pause (from the same LCM instance) has been handled.
TEST_F(MultiController, DuplicateMuscleAcrossMessagesIsRejectedAndCounted) {
  const std::string url = bus_url(7832);
  ServerController first(url), second(url);
  ASSERT_TRUE(first.good() && second.good());
  auto server = start_server(url, "run", {"--controllers", "2"});
  ASSERT_TRUE(first.wait_step(0)) << server->stderr_text();
  ASSERT_TRUE(second.wait_step(0)) << server->stderr_text();
  const auto paused = [](const lcmt_tongue_state& s) { return s.status == "paused"; };

  first.send_activation(1, {"flexor"}, {0.5});
  first.send_command("pause");
  const auto after_first = first.wait_state(paused);
  ASSERT_TRUE(after_first) << server->stderr_text();
  EXPECT_EQ(after_first->step, 0);  // 1 of 2: no step yet
  EXPECT_EQ(after_first->rejected_messages, 0);
  ASSERT_TRUE(second.wait_state(paused));  // the same paused state, out of second's queue

  second.send_activation(1, {"extensor", "flexor"}, {0.2, 0.3});  // flexor is taken
  second.send_command("pause");
  const auto after_duplicate = second.wait_state(paused);
  ASSERT_TRUE(after_duplicate) << server->stderr_text();
  EXPECT_EQ(after_duplicate->step, 0);
  EXPECT_EQ(after_duplicate->rejected_messages, 1);
  EXPECT_EQ(after_duplicate->activations, (std::vector<double>{0.0, 0.0}));

  second.send_command("resume");
  second.send_activation(1, {"extensor"}, {0.2});
  const auto s1 = second.wait_step(1);
  ASSERT_TRUE(s1) << server->stderr_text();
  EXPECT_EQ(s1->activations, (std::vector<double>{0.5, 0.2}));  // not the rejected 0.3
  EXPECT_EQ(s1->rejected_messages, 1);
  second.send_command("shutdown");
  EXPECT_EQ(server->wait_exit(kExitWaitMs), 0) << server->stderr_text();
  EXPECT_NE(server->stderr_text().find("rejected overlapping activation at step 0: \"flexor\" is "
                                       "already set for step 1 by an earlier message"),
            std::string::npos)
      << server->stderr_text();
}

// With 1 of 2 activations the server does not advance; the timeout report says how many came;
// the second one makes the step.
TEST_F(MultiController, DoesNotAdvanceWithOneOfTwoActivations) {
  const std::string url = bus_url(7833);
  ServerController first(url), second(url);
  ASSERT_TRUE(first.good() && second.good());
  auto server = start_server(url, "run", {"--controllers", "2", "--timeout-ms", "200"});
  ASSERT_TRUE(first.wait_step(0)) << server->stderr_text();
  first.send_activation(1, {"flexor"}, {0.5});
  // Two reports (at least 400 ms) with no state of step 1.
  ASSERT_TRUE(server->wait_stderr(
      "1 of 2 activations for step 1 within 200 ms, holding\nsim_server: 1 of 2 activations "
      "for step 1 within 200 ms, holding"))
      << server->stderr_text();
  EXPECT_FALSE(first.wait_step(1, 100)) << "the server advanced with 1 of 2 activations";
  second.send_activation(1, {"extensor"}, {0.25});
  const auto s1 = first.wait_step(1);
  ASSERT_TRUE(s1) << server->stderr_text();
  EXPECT_EQ(s1->activations, (std::vector<double>{0.5, 0.25}));
  EXPECT_EQ(s1->rejected_messages, 0);
  first.send_command("shutdown");
  EXPECT_EQ(server->wait_exit(kExitWaitMs), 0) << server->stderr_text();
}

TEST_F(MultiController, SilenceWithOneOfTwoStopsWhenAskedTo) {
  const std::string url = bus_url(7834);
  ServerController first(url);
  ASSERT_TRUE(first.good());
  auto server = start_server(url, "run",
                             {"--controllers", "2", "--timeout-ms", "200", "--on-silence", "stop"});
  ASSERT_TRUE(first.wait_step(0)) << server->stderr_text();
  first.send_activation(1, {"flexor"}, {0.5});
  EXPECT_EQ(server->wait_exit(kExitWaitMs), 3) << server->stderr_text();
  EXPECT_NE(server->stderr_text().find("1 of 2 activations for step 1 within 200 ms: stopping"),
            std::string::npos)
      << server->stderr_text();
  const testing::RunFile run(dir_ / "run.h5");
  EXPECT_EQ(run.string_attribute("/", "status"),
            "stopped: 1 of 2 activations for step 1 within 200 ms");
  EXPECT_EQ(run.doubles("/time").size(), 1u);
}

TEST_F(MultiController, SeveralControllersNeedLockStepAndAtLeastOne) {
  const std::string scene = (dir_ / "scene.yaml").string();
  const std::string url = bus_url(7835);
  for (const std::string mode : {"fast", "realtime"}) {
    const testing::RunResult r = testing::run_command(
        SIM_SERVER_PATH,
        "'" + scene + "' --controllers 2 --mode " + mode + " --lcm-url '" + url + "'", dir_);
    EXPECT_EQ(r.exit_code, 1) << mode;
    EXPECT_NE(r.err.find("--controllers applies to --mode lockstep only"), std::string::npos)
        << r.err;
  }
  for (const std::string bad : {"0", "-1", "two"}) {
    const testing::RunResult r = testing::run_command(
        SIM_SERVER_PATH, "'" + scene + "' --controllers " + bad + " --lcm-url '" + url + "'", dir_);
    EXPECT_EQ(r.exit_code, 1) << bad;
    EXPECT_NE(r.err.find("--controllers must be an integer in [1, 1000000]"), std::string::npos)
        << r.err;
  }
}

}  // namespace
}  // namespace tongue::server
