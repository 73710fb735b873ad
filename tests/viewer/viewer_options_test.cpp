// tongue_viewer's command line.
#include "viewer/viewer_options.hpp"

#include <gtest/gtest.h>

namespace tongue::viewer {
namespace {

ViewerOptions parse(std::vector<std::string> args) {
  return parse_viewer_options(args);
}

TEST(ViewerOptions, LiveOnLocalhostByDefault) {
  const ViewerOptions o = parse({});
  EXPECT_FALSE(o.replay());
  EXPECT_EQ(o.listen_address, "127.0.0.1");
  EXPECT_EQ(o.listen_port, 8080);
  EXPECT_EQ(o.prefix, "TONGUE_");
}

TEST(ViewerOptions, ReplayOfARunAndItsReference) {
  const ViewerOptions o = parse({"--run", "a.h5", "--run", "b.h5", "--listen", "0.0.0.0:0"});
  EXPECT_EQ(o.run_files, (std::vector<std::string>{"a.h5", "b.h5"}));
  EXPECT_EQ(o.listen_address, "0.0.0.0");
  EXPECT_EQ(o.listen_port, 0);
}

void expect_refused(std::vector<std::string> args, const std::string& words) {
  try {
    parse(args);
    ADD_FAILURE() << "accepted; expected: " << words;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(ViewerOptions, BadCommandLinesSayWhy) {
  expect_refused({"--listen", "8080"}, "--listen wants ADDR:PORT");
  expect_refused({"--listen", "localhost:99999"}, "is not a number in 0-65535");
  expect_refused({"--listen", "localhost:80x"}, "is not a number in 0-65535");
  expect_refused({"--run"}, "--run needs a value");
  expect_refused({"--run", "a", "--run", "b", "--run", "c"}, "--run at most twice");
  expect_refused({"--run", "a", "--prefix", "X_"}, "--lcm-url and --prefix are for live viewing");
  expect_refused({"--prefix", "lower"}, "lower");
  expect_refused({"--frobnicate"}, "unexpected argument");
}

}  // namespace
}  // namespace tongue::viewer
