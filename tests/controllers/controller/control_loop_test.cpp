// The control loop every controller shares (controllers/controller/control_loop.hpp), end to end:
// sequence_player (the simplest controller) against the real sim_server on the box scene of
// sim_server_driver.hpp, over udpm on the loopback, one port per test (7800-7809).
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "sequence_player/activation_sequence.hpp"
#include "support/run_command.hpp"
#include "support/run_file.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif
#ifndef SEQUENCE_PLAYER_PATH
#error "SEQUENCE_PLAYER_PATH must name the sequence_player executable"
#endif
#ifndef EP_CONTROLLER_PATH
#error "EP_CONTROLLER_PATH must name the ep_controller executable"
#endif
#ifndef REPLAY_PATH
#error "REPLAY_PATH must name the replay executable"
#endif

namespace tongue::controller {
namespace {

namespace fs = std::filesystem;
using tongue::testing::bus_url;
using tongue::testing::ChildProcess;
using tongue::testing::kBoxScene;
using tongue::testing::ServerController;

constexpr int kExitWaitMs = 10000;  // longest wait for a process to end
constexpr double kBoxDt = 0.002;    // s, the box scene's

// A ramp of the box's one muscle: every step a different level, so a step off by one shows.
const char* const kRamp = R"(
entries:
  - {muscle: flexor, start: 0.0, end: 0.1, level_from: 0.0, level_to: 1.0}
)";

// Commands seen on the command channel of a bus (the controller's describe, pause, resume).
class CommandListener {
 public:
  explicit CommandListener(const std::string& url) : lcm_(url) {
    lcm_.subscribe(bus::Channels{}.command, &CommandListener::on_command, this);
  }
  void poll_for(int ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    while (std::chrono::steady_clock::now() < end) lcm_.handleTimeout(10);
  }
  int count(const std::string& command) const {
    int n = 0;
    for (const std::string& c : commands_) n += c == command;
    return n;
  }

 private:
  void on_command(const lcm::ReceiveBuffer*, const std::string&,
                  const tongue_lcm::lcmt_tongue_command* msg) {
    commands_.push_back(msg->command);
  }
  lcm::LCM lcm_;
  std::vector<std::string> commands_;
};

class ControlLoop : public tongue::testing::TempDirTest {
 protected:
  std::unique_ptr<ChildProcess> server(int port, std::vector<std::string> extra = {}) {
    std::vector<std::string> args{write("box.yaml", kBoxScene), "--lcm-url", bus_url(port),
                                  "--output", (dir_ / "run.h5").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return std::make_unique<ChildProcess>(SIM_SERVER_PATH, args, dir_, "server");
  }
  std::unique_ptr<ChildProcess> player(int port, const std::string& schedule,
                                       std::vector<std::string> extra = {}) {
    std::vector<std::string> args{"--schedule", write("schedule.yaml", schedule), "--lcm-url",
                                  bus_url(port)};
    args.insert(args.end(), extra.begin(), extra.end());
    return std::make_unique<ChildProcess>(SEQUENCE_PLAYER_PATH, args, dir_, "player");
  }
  // Levels of the box's muscle the schedule gives for steps 1..steps.
  std::vector<double> expected_levels(const std::string& schedule, int steps) {
    const sequence_player::ActivationSequence s(
        sequence_player::parse_sequence(schedule, "schedule.yaml"), {"flexor"}, {0.01});
    std::vector<double> out{0.0};  // step 0: every muscle off
    for (int k = 1; k <= steps; ++k) out.push_back(s.levels_at(k * kBoxDt).levels.at(0));
    return out;
  }
};

TEST_F(ControlLoop, NoServerIsExit4AfterTheTimeoutHavingAskedForTheModel) {
  const int port = 7800;
  CommandListener listener(bus_url(port));
  const auto start = std::chrono::steady_clock::now();
  auto p = player(port, kRamp, {"--timeout-s", "0.7"});
  EXPECT_EQ(p->wait_exit(kExitWaitMs), 4) << p->stderr_text();
  listener.poll_for(200);  // what it sent waits in the listener's socket until then
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(took, 0.7);  // waited the whole timeout
  const std::string err = p->stderr_text();
  EXPECT_NE(err.find("no model on TONGUE_MODEL"), std::string::npos) << err;
  EXPECT_NE(err.find("0 states received"), std::string::npos) << err;
  // describe after 200 ms, then 400 ms later (backing off, not flooding): one or two within 0.7 s
  // (the second may fall after the timeout on a loaded machine).
  EXPECT_GE(listener.count("describe"), 1);
  EXPECT_LE(listener.count("describe"), 2);
}

TEST_F(ControlLoop, LockStepSendsTheLevelOfEachStepAndEndsAtMaxSteps) {
  const int port = 7801;
  ServerController bus(bus_url(port));
  auto s = server(port);
  auto p = player(port, kRamp, {"--max-steps", "10"});
  ASSERT_EQ(p->wait_exit(kExitWaitMs), 0) << p->stderr_text() << s->stderr_text();
  const std::string err = p->stderr_text();
  EXPECT_NE(err.find("reached step 10 (--max-steps); 11 states received (steps 0-10), 10 "
                     "activations sent (lockstep)"),
            std::string::npos)
      << err;
  // The server got nothing for step 11: it still waits at step 10.
  ASSERT_TRUE(bus.wait_step(10));
  EXPECT_FALSE(bus.wait_step(11, 500));
  bus.send_command("shutdown");
  ASSERT_EQ(s->wait_exit(kExitWaitMs), 0) << s->stderr_text();
  const tongue::testing::RunFile run(dir_ / "run.h5");
  EXPECT_EQ(run.doubles("/activations"), expected_levels(kRamp, 10));
}

// The real-time server does not wait for its controller: the player is started first and the
// server only once the player asks for the model (it is then listening), so that the player's
// answers reach the server long before its last step (250 steps of 2 ms: 0.5 s).
TEST_F(ControlLoop, RealTimeAnswersEachStateWithApplyNow) {
  const int port = 7802;
  ServerController bus(bus_url(port));
  CommandListener listener(bus_url(port));
  auto p = player(port, "entries: [{muscle: flexor, level: 0.5}]",
                  {"--mode", "realtime", "--max-steps", "250"});
  for (int waited = 0; listener.count("describe") == 0 && waited < kExitWaitMs; waited += 50)
    listener.poll_for(50);
  ASSERT_GE(listener.count("describe"), 1) << p->stderr_text();
  auto s = server(port, {"--mode", "realtime", "--max-steps", "250"});
  const auto last = bus.wait_step(250, kExitWaitMs);
  ASSERT_TRUE(last) << s->stderr_text() << p->stderr_text();
  EXPECT_EQ(last->activations, (std::vector<double>{0.5}));
  EXPECT_EQ(last->rejected_messages, 0);  // step -1 is what a real-time server takes
  EXPECT_EQ(s->wait_exit(kExitWaitMs), 0) << s->stderr_text();
  EXPECT_EQ(p->wait_exit(kExitWaitMs), 0) << p->stderr_text();
  EXPECT_NE(p->stderr_text().find("activations sent (realtime)"), std::string::npos)
      << p->stderr_text();
}

// A controller started after the server has published state 0 (as an experiment runner starts
// them): describe brings the model and the state the server waits on.
TEST_F(ControlLoop, ControllerStartedLateJoinsTheRun) {
  const int port = 7803;
  ServerController bus(bus_url(port));
  CommandListener listener(bus_url(port));
  auto s = server(port);
  ASSERT_TRUE(bus.wait_step(0, kExitWaitMs)) << s->stderr_text();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // state 0 is long gone
  auto p = player(port, kRamp, {"--max-steps", "5"});
  ASSERT_EQ(p->wait_exit(kExitWaitMs), 0) << p->stderr_text() << s->stderr_text();
  listener.poll_for(100);
  EXPECT_GE(listener.count("describe"), 1);
  EXPECT_EQ(listener.count("pause"), 0);
  const auto s5 = bus.wait_step(5);
  ASSERT_TRUE(s5);
  EXPECT_EQ(s5->rejected_messages, 0);  // state 0 was answered once
  bus.send_command("shutdown");
  ASSERT_EQ(s->wait_exit(kExitWaitMs), 0) << s->stderr_text();
  const tongue::testing::RunFile run(dir_ / "run.h5");
  EXPECT_EQ(run.doubles("/activations"), expected_levels(kRamp, 5));
}

// SIGINT and SIGTERM end the controller cleanly (exit 0) with its summary.
TEST_F(ControlLoop, SignalsEndCleanlyWithASummary) {
  for (const auto& [port, sig, name] : std::vector<std::tuple<int, int, std::string>>{
           {7804, SIGINT, "SIGINT"}, {7805, SIGTERM, "SIGTERM"}}) {
    ServerController bus(bus_url(port));
    auto s = server(port);
    auto p = player(port, kRamp);
    ASSERT_TRUE(bus.wait_step(20, kExitWaitMs)) << p->stderr_text();
    p->signal(sig);
    ASSERT_EQ(p->wait_exit(kExitWaitMs), 0) << p->stderr_text();
    const std::string err = p->stderr_text();
    EXPECT_NE(err.find("sequence_player: stopped by " + name + ";"), std::string::npos) << err;
    EXPECT_NE(err.find("activations sent"), std::string::npos) << err;
    bus.send_command("shutdown");
    EXPECT_EQ(s->wait_exit(kExitWaitMs), 0);
  }
}

TEST_F(ControlLoop, SilenceAfterTheFirstStateIsExit4) {
  const int port = 7806;
  auto s = server(port, {"--max-steps", "3"});  // ends after step 3
  auto p = player(port, kRamp, {"--timeout-s", "0.5"});
  EXPECT_EQ(s->wait_exit(kExitWaitMs), 0) << s->stderr_text();
  EXPECT_EQ(p->wait_exit(kExitWaitMs), 4) << p->stderr_text();
  EXPECT_NE(p->stderr_text().find("no state for 0.5 s after step 3"), std::string::npos)
      << p->stderr_text();
}

TEST_F(ControlLoop, ScheduleThatDoesNotFitTheServerIsExit1NamingFileAndKey) {
  const int port = 7807;
  auto s = server(port);
  auto p = player(port, "entries: [{muscle: flexor, level: 0.1}, {muscle: SG, level: 0.2}]");
  EXPECT_EQ(p->wait_exit(kExitWaitMs), 1) << p->stderr_text();
  const std::string err = p->stderr_text();
  EXPECT_NE(err.find((dir_ / "schedule.yaml").string() + ": entries[1].muscle: no muscle is named "
                                                         "'SG'"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("flexor"), std::string::npos) << err;  // lists the server's muscles
}

// Bad command lines and input files end every program with exit 1 before it touches the bus,
// naming the option, or the file and the key.
TEST_F(ControlLoop, BadCommandLinesAndFilesAreExit1) {
  struct Case {
    std::string program, args, expected;
  };
  const std::string plan = write("plan.yaml", "delta_lambda_mm: {SG: [1, oops]}");
  const std::string schedule = write("bad_schedule.yaml", "entries: [{muscle: SG, levl: 1}]");
  const std::string not_a_log = write("run.h5", "not HDF5");
  const std::vector<Case> cases = {
      {EP_CONTROLLER_PATH, "", "--plan is required"},
      {EP_CONTROLLER_PATH, "--plan '" + plan + "'",
       plan + ": delta_lambda_mm.SG[1]: expected a number"},
      {EP_CONTROLLER_PATH, "--plan /nonexistent.yaml", "/nonexistent.yaml: cannot open the file"},
      {EP_CONTROLLER_PATH, "--plan '" + plan + "' --delay-ms -3", "--delay-ms must be in"},
      {EP_CONTROLLER_PATH, "--plan '" + plan + "' --velocity-factor maybe", "--velocity-factor"},
      {SEQUENCE_PLAYER_PATH, "--schedule '" + schedule + "'",
       schedule + ": entries[0].levl: unknown key"},
      {SEQUENCE_PLAYER_PATH, "--schedule x.yaml --mode fast",
       "--mode must be lockstep or realtime"},
      {REPLAY_PATH, "--log '" + not_a_log + "'", not_a_log + ": cannot open as an HDF5 run file"},
      {REPLAY_PATH, "--log x.h5 --max-steps ten", "--max-steps must be an integer"},
  };
  for (const Case& c : cases) {
    const tongue::testing::RunResult r = tongue::testing::run_command(c.program, c.args, dir_);
    EXPECT_EQ(r.exit_code, 1) << c.program << " " << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << "\n" << r.err;
  }
  // --help: the usage with the common options, exit 0.
  for (const std::string program : {EP_CONTROLLER_PATH, SEQUENCE_PLAYER_PATH, REPLAY_PATH}) {
    const tongue::testing::RunResult r = tongue::testing::run_command(program, "--help", dir_);
    EXPECT_EQ(r.exit_code, 0) << program;
    EXPECT_NE(r.out.find("--timeout-s"), std::string::npos) << r.out;
  }
}

}  // namespace
}  // namespace tongue::controller
