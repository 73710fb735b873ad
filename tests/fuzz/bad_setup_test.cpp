// Bad setups caught before anything runs: the URLs liblcm would take silently (empty, an unknown
// option, "ttl=abc"), a prefix too long for LCM's channel names, and a scene path that never
// ends (/dev/zero), each a clear error with exit 1 from sim_server, sim_command and a controller.
#include <gtest/gtest.h>

#include <string>

#include "support/run_command.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif
#ifndef SIM_COMMAND_PATH
#error "SIM_COMMAND_PATH must name the sim_command executable"
#endif
#ifndef EP_CONTROLLER_PATH
#error "EP_CONTROLLER_PATH must name the ep_controller executable"
#endif

namespace tongue::fuzz {
namespace {

class BadSetup : public testing::TempDirTest {
 protected:
  // Runs program with args; expects exit 1 and expected in its stderr.
  void expect_refused(const char* program, const std::string& args, const std::string& expected) {
    const auto r = testing::run_command(program, args, dir_);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
  }
  // The box scene's path, quoted for the shell.
  std::string scene() const {
    std::string quoted(1, '\'');
    quoted += write("box.yaml", testing::kBoxScene);
    quoted += '\'';
    return quoted;
  }
};

TEST_F(BadSetup, BadUrlsAreRefusedUpFront) {
  const std::pair<std::string, std::string> cases[] = {
      {"''", "empty"},
      {"'udpm://239.255.76.67:7941?ttl=abc'", "ttl must be"},
      {"'udpm://239.255.76.67:7941?ttl=0&colour=red'", "unknown udpm option 'colour'"},
      {"'udpm://239.255.76.67'", "GROUP:PORT"},
  };
  for (const auto& [url, expected] : cases) {
    expect_refused(SIM_SERVER_PATH, scene() + " --lcm-url " + url, expected);
    expect_refused(SIM_COMMAND_PATH, "pause --lcm-url " + url, expected);
    expect_refused(EP_CONTROLLER_PATH, "--plan x.yaml --lcm-url " + url, expected);
  }
}

// 300 characters passed the old check and failed at the first publish.
TEST_F(BadSetup, APrefixTooLongForLcmIsRefused) {
  const std::string prefix(300, 'A');
  expect_refused(SIM_SERVER_PATH, scene() + " --prefix " + prefix, "at most 53 characters");
  expect_refused(SIM_COMMAND_PATH, "pause --prefix " + prefix, "at most 53 characters");
  expect_refused(EP_CONTROLLER_PATH, "--plan x.yaml --prefix " + prefix, "at most 53 characters");
}

TEST_F(BadSetup, DevZeroAsTheSceneIsAClearError) {
  expect_refused(SIM_SERVER_PATH, "/dev/zero --lcm-url udpm://239.255.76.67:7941?ttl=0",
                 "/dev/zero: the file is larger than");
}

}  // namespace
}  // namespace tongue::fuzz
