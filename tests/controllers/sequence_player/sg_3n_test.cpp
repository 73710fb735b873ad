// The paper's SG 3 N experiment two ways: sim_batch runs scenes/tongue_sg_3n.yaml with the
// scene's own activation schedule; sim_server runs the same scene (it ignores the schedule) driven
// over udpm (port 7810) by sequence_player playing sequences/sg_3n.yaml. Both apply level
// 3 N / 24 N to SG_left and SG_right for the steps ending at 4 ... 120 ms from the same settled
// state through the same integrator, so the run files agree bit for bit.
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
#ifndef SIM_BATCH_PATH
#error "SIM_BATCH_PATH must name the sim_batch executable"
#endif
#ifndef SEQUENCE_PLAYER_PATH
#error "SEQUENCE_PLAYER_PATH must name the sequence_player executable"
#endif
#ifndef PROJECT_DIR
#error "PROJECT_DIR must name the project's source directory"
#endif

namespace tongue::controller {
namespace {

namespace fs = std::filesystem;
using tongue::testing::bus_url;
using tongue::testing::ChildProcess;
using tongue::testing::RunFile;

constexpr int kRunWaitMs = 120000;  // 30 full-Newton tongue steps and the settling (about 5 s)

class Sg3n : public tongue::testing::TempDirTest {};

TEST_F(Sg3n, SequencePlayerThroughTheServerReproducesSimBatch) {
  const std::string scene = PROJECT_DIR "/scenes/tongue_sg_3n.yaml";
  const fs::path batch = dir_ / "batch.h5", served = dir_ / "served.h5";
  const tongue::testing::RunResult r = tongue::testing::run_command(
      SIM_BATCH_PATH, "'" + scene + "' --quiet --output '" + batch.string() + "'", dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const std::string url = bus_url(7810);
  ChildProcess player(SEQUENCE_PLAYER_PATH,
                      {"--schedule", PROJECT_DIR "/controllers/sequences/sg_3n.yaml", "--lcm-url",
                       url, "--timeout-s", "60"},
                      dir_, "player");
  // No --max-steps: the schedule's duration ends the player after step 30; the server is told.
  ChildProcess server(SIM_SERVER_PATH,
                      {scene, "--lcm-url", url, "--output", served.string(), "--max-steps", "30",
                       "--nodes", "landmarks"},
                      dir_, "server");
  ASSERT_EQ(player.wait_exit(kRunWaitMs), 0) << player.stderr_text();
  ASSERT_EQ(server.wait_exit(kRunWaitMs), 0) << server.stderr_text();
  EXPECT_NE(player.stderr_text().find("reached step 30 (the controller's last step)"),
            std::string::npos)
      << player.stderr_text();

  const RunFile a(batch), b(served);
  ASSERT_TRUE(a.ok());
  ASSERT_TRUE(b.ok());
  ASSERT_EQ(a.shape("/positions"), b.shape("/positions"));
  EXPECT_EQ(a.shape("/positions").at(0), 31u);  // 120 ms in 4 ms steps, and the start
  EXPECT_EQ(a.doubles("/time"), b.doubles("/time"));
  EXPECT_EQ(a.doubles("/activations"), b.doubles("/activations"));
  EXPECT_EQ(a.doubles("/positions"), b.doubles("/positions"));  // bit for bit
  const std::vector<double> p = b.doubles("/positions");
  EXPECT_NE(std::vector<double>(p.begin(), p.begin() + 3003),
            std::vector<double>(p.end() - 3003, p.end()));  // SG moved the tongue
}

}  // namespace
}  // namespace tongue::controller
