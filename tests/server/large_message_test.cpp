// Messages larger than the kernel's default socket receive buffer: the refined tongue's model
// (about 350 kB) and states (about 190 kB) are sent in many UDP fragments at once, and a
// receiver whose buffer cannot hold them all loses the message. With the receive buffer the
// default bus URL asks for (bus::kDefaultLcmUrl: 4 MB), they arrive whole even when the receiver
// is busy while they are sent. (Without it this test fails: the model is lost.)
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>

#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif

namespace tongue::server {
namespace {

using testing::bus_url;
using testing::ChildProcess;
using testing::ServerController;

// The built-in tongue at refinement 2 (6825 nodes, 5760 hexahedra), not settled, so that it
// starts quickly; one muscle is enough to step it.
constexpr const char* kRefinedTongue = R"(
mesh:
  tongue: {refinement: 2}
material: {type: mooney_rivlin5, parameters: {poisson_ratio: 0.49}}
constraints:
  - {set: mandible, components: [x, y, z]}
muscles: builtin
damping: {beta: 0.028}
analysis: {type: dynamic, duration: 0.004, dt: 0.004}
solver: {max_tangent_reuse: 20}
)";

// The kernel's cap on a socket's receive buffer [bytes] (net.core.rmem_max), 0 if unknown.
long receive_buffer_cap() {
  std::ifstream in("/proc/sys/net/core/rmem_max");
  long cap = 0;
  in >> cap;
  return cap;
}

class LargeMessages : public testing::TempDirTest {};

TEST_F(LargeMessages, RefinedTongueModelAndStatesArriveWhole) {
  constexpr int kBuffer = 4194304;  // bytes, as in bus::kDefaultLcmUrl
  // Model and state 0 together are about 540 kB; a kernel capping buffers below 1 MB cannot hold
  // them whatever the URL asks (README: raise net.core.rmem_max).
  if (receive_buffer_cap() < 1048576) {
    GTEST_SKIP() << "net.core.rmem_max is " << receive_buffer_cap() << " bytes (< 1 MB)";
  }
  const std::string url = bus_url(7871, kBuffer);
  ServerController controller(url);
  ASSERT_TRUE(controller.good());
  ChildProcess server(
      SIM_SERVER_PATH,
      {write("scene.yaml", kRefinedTongue), "--lcm-url", url, "--timeout-ms", "100"}, dir_);
  // The controller is busy (reads nothing) until the server has sent the model and state 0 and
  // reports waiting for step 1: both must then be waiting whole in the socket's buffer.
  constexpr int kStartupMs = 60000;  // building the refined tongue takes a few seconds
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::milliseconds(kStartupMs);
  while (server.stderr_text().find("no activation for step 1") == std::string::npos) {
    ASSERT_LT(std::chrono::steady_clock::now(), give_up) << server.stderr_text();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const auto model = controller.wait_model(kStartupMs);
  ASSERT_TRUE(model) << server.stderr_text();
  EXPECT_EQ(model->num_nodes, 6825);
  EXPECT_EQ(model->num_elements, 5760);
  const auto s0 = controller.wait_step(0, kStartupMs);
  ASSERT_TRUE(s0) << server.stderr_text();
  EXPECT_EQ(s0->num_nodes, 6825);
  controller.send_activation(1, {"SG_left", "SG_right"}, {0.1, 0.1});
  const auto s1 = controller.wait_step(1, kStartupMs);
  ASSERT_TRUE(s1) << server.stderr_text();
  EXPECT_TRUE(s1->converged);
  EXPECT_EQ(s1->positions.size(), 3u * 6825u);
  controller.send_command("shutdown");
  EXPECT_EQ(server.wait_exit(10000), 0) << server.stderr_text();
}

}  // namespace
}  // namespace tongue::server
