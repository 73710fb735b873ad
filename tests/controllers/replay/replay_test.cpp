// replay end to end: a run driven by a controller through the real sim_server is replayed from
// its run file into a fresh server on the same scene, and the new run file's positions equal the
// original's bit for bit. Ports 7811-7816, one per server run.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

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
#ifndef PROJECT_DIR
#error "PROJECT_DIR must name the project's source directory"
#endif

namespace tongue::controller {
namespace {

namespace fs = std::filesystem;
using tongue::testing::bus_url;
using tongue::testing::ChildProcess;
using tongue::testing::kBoxScene;
using tongue::testing::RunFile;

constexpr int kRunWaitMs = 60000;  // a few seconds of tongue steps, generously

// Steps, ramps and an override on the box's one muscle: a different level nearly every step.
const char* const kSchedule = R"(
entries:
  - {muscle: flexor, start: 0.0, end: 0.03, level_from: 0.0, level_to: 0.9}
  - {muscle: flexor, start: 0.03, end: 0.05, level: 0.35}
  - {muscle: flexor, start: 0.04, end: 0.046, level: 1.0}
)";

class Replay : public tongue::testing::TempDirTest {
 protected:
  // Runs sim_server on scene (run file `name`.h5) for steps steps, driven by the controller
  // program with args (the bus options appended); both must end with exit 0.
  fs::path run(int port, const std::string& scene, const std::string& name,
               const std::string& program, std::vector<std::string> args, int steps) {
    const std::string url = bus_url(port), n = std::to_string(steps);
    const fs::path out = dir_ / (name + ".h5");
    for (const std::string& a : {std::string("--lcm-url"), url, std::string("--max-steps"), n,
                                 std::string("--timeout-s"), std::string("30")})
      args.push_back(a);
    ChildProcess controller(program, args, dir_, name + "_controller");
    ChildProcess server(SIM_SERVER_PATH,
                        {scene, "--lcm-url", url, "--output", out.string(), "--max-steps", n}, dir_,
                        name + "_server");
    EXPECT_EQ(controller.wait_exit(kRunWaitMs), 0) << controller.stderr_text();
    EXPECT_EQ(server.wait_exit(kRunWaitMs), 0) << server.stderr_text();
    last_controller_err_ = controller.stderr_text();
    return out;
  }

  void expect_same_run(const fs::path& original, const fs::path& replayed) {
    const RunFile a(original), b(replayed);
    ASSERT_TRUE(a.ok());
    ASSERT_TRUE(b.ok());
    const std::vector<double> p = a.doubles("/positions");
    ASSERT_FALSE(p.empty());
    EXPECT_EQ(b.doubles("/positions"), p);  // bit for bit
    EXPECT_EQ(b.doubles("/activations"), a.doubles("/activations"));
    EXPECT_EQ(b.doubles("/time"), a.doubles("/time"));
    const std::vector<std::size_t> shape = a.shape("/positions");
    const std::size_t frame = shape.at(1) * 3;
    EXPECT_NE(std::vector<double>(p.begin(), p.begin() + frame),
              std::vector<double>(p.end() - frame, p.end()));  // the muscles moved something
  }

  std::string last_controller_err_;
};

TEST_F(Replay, SequencePlayerRunOnTheBoxReplaysBitForBit) {
  const std::string scene = write("box.yaml", kBoxScene);
  const fs::path original = run(7811, scene, "original", SEQUENCE_PLAYER_PATH,
                                {"--schedule", write("schedule.yaml", kSchedule)}, 30);
  const fs::path replayed =
      run(7812, scene, "replayed", REPLAY_PATH, {"--log", original.string()}, 30);
  expect_same_run(original, replayed);
}

// The replay needs no --max-steps: it ends after the log's last step.
TEST_F(Replay, EpControllerRunOnTheTongueReplaysBitForBitAndEndsWithTheLog) {
  const std::string scene = PROJECT_DIR "/scenes/tongue_ep.yaml";
  const fs::path original = run(7813, scene, "original", EP_CONTROLLER_PATH,
                                {"--plan", PROJECT_DIR "/controllers/plans/ai.yaml"}, 50);
  const std::string url = bus_url(7814);
  const fs::path replayed = dir_ / "replayed.h5";
  ChildProcess replay(REPLAY_PATH, {"--log", original.string(), "--lcm-url", url}, dir_, "replay");
  ChildProcess server(SIM_SERVER_PATH,
                      {scene, "--lcm-url", url, "--output", replayed.string(), "--max-steps", "50"},
                      dir_, "replayed_server");
  ASSERT_EQ(replay.wait_exit(kRunWaitMs), 0) << replay.stderr_text();
  ASSERT_EQ(server.wait_exit(kRunWaitMs), 0) << server.stderr_text();
  // 51 states, or 52 when the server answered the replayer's early describe with state 0 again.
  EXPECT_NE(replay.stderr_text().find("states received (steps 0-50), 50 activations sent"),
            std::string::npos)
      << replay.stderr_text();
  expect_same_run(original, replayed);
}

TEST_F(Replay, LogOfAnotherSceneIsExit1NamingTheFileAndTheMuscles) {
  const fs::path original =
      run(7815, write("box.yaml", kBoxScene), "original", SEQUENCE_PLAYER_PATH,
          {"--schedule", write("schedule.yaml", kSchedule)}, 5);
  std::string other = kBoxScene;
  other.replace(other.find("name: flexor"), 12, "name: extensor");
  const std::string url = bus_url(7816);
  ChildProcess server(SIM_SERVER_PATH, {write("other.yaml", other), "--lcm-url", url}, dir_,
                      "other_server");
  ChildProcess replay(REPLAY_PATH, {"--log", original.string(), "--lcm-url", url}, dir_, "replay");
  EXPECT_EQ(replay.wait_exit(kRunWaitMs), 1) << replay.stderr_text();
  const std::string err = replay.stderr_text();
  EXPECT_NE(err.find(original.string() + ": /muscles/names: the log's muscles (flexor) are not "
                                         "the server's (extensor)"),
            std::string::npos)
      << err;
}

}  // namespace
}  // namespace tongue::controller
