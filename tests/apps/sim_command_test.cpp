// sim_command end to end: the real executable steers a real sim_server (box scene, lock-step) on
// a udpm bus of its own port; the test watches the states the server publishes in answer.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/run_command.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif
#ifndef SIM_COMMAND_PATH
#error "SIM_COMMAND_PATH must name the sim_command executable"
#endif

namespace tongue::apps {
namespace {

using testing::bus_url;
using testing::ChildProcess;
using testing::kBoxScene;
using testing::run_command;
using testing::ServerController;

class SimCommand : public testing::TempDirTest {};

TEST_F(SimCommand, PausesAndShutsDownARunningServer) {
  const std::string url = bus_url(7870);
  ServerController watcher(url);
  ASSERT_TRUE(watcher.good());
  ChildProcess server(SIM_SERVER_PATH, {write("scene.yaml", kBoxScene), "--lcm-url", url}, dir_);
  ASSERT_TRUE(watcher.wait_step(0)) << server.stderr_text();

  const std::string target = "--lcm-url '" + url + "'";
  ASSERT_EQ(run_command(SIM_COMMAND_PATH, "pause " + target, dir_).exit_code, 0);
  const auto paused = watcher.wait_state(
      [](const tongue_lcm::lcmt_tongue_state& s) { return s.status == "paused"; });
  EXPECT_TRUE(paused) << server.stderr_text();

  ASSERT_EQ(run_command(SIM_COMMAND_PATH, "shutdown " + target, dir_).exit_code, 0);
  EXPECT_EQ(server.wait_exit(5000), 0) << server.stderr_text();
}

TEST_F(SimCommand, RejectsAnUnknownCommandAndABadPrefix) {
  const auto unknown = run_command(SIM_COMMAND_PATH, "explode", dir_);
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.err.find("unexpected argument \"explode\""), std::string::npos) << unknown.err;
  const auto prefix = run_command(SIM_COMMAND_PATH, "pause --prefix bad-prefix", dir_);
  EXPECT_EQ(prefix.exit_code, 1);
  EXPECT_NE(prefix.err.find("UPPER_SNAKE"), std::string::npos) << prefix.err;
}

}  // namespace
}  // namespace tongue::apps
