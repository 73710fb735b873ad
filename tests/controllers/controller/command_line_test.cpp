#include "controller/command_line.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tongue::controller {
namespace {

CommandLine parse(std::vector<const char*> args, const std::vector<std::string>& own = {"--plan"}) {
  args.insert(args.begin(), "program");
  return parse_command_line(static_cast<int>(args.size()), args.data(), own);
}

TEST(CommandLine, DefaultsAreTheDocumentedOnes) {
  const CommandLine c = parse({"--plan", "p.yaml"});
  EXPECT_EQ(c.common.lcm_url, "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304");
  EXPECT_EQ(c.common.prefix, "TONGUE_");
  EXPECT_EQ(c.common.mode, LoopMode::lockstep);
  EXPECT_FALSE(c.common.max_steps.has_value());
  EXPECT_EQ(c.common.timeout_s, 5.0);
  EXPECT_EQ(c.values.at("--plan"), "p.yaml");
  EXPECT_FALSE(c.help);
}

TEST(CommandLine, ReadsEveryCommonOptionInBothSpellings) {
  const CommandLine c =
      parse({"--lcm-url=udpm://239.255.76.67:7801?ttl=0", "--prefix", "T2_", "--mode=realtime",
             "--max-steps", "30", "--timeout-s=0.5", "--plan=x.yaml"});
  EXPECT_EQ(c.common.lcm_url, "udpm://239.255.76.67:7801?ttl=0");
  EXPECT_EQ(c.common.prefix, "T2_");
  EXPECT_EQ(c.common.mode, LoopMode::realtime);
  EXPECT_EQ(c.common.max_steps, 30);
  EXPECT_EQ(c.common.timeout_s, 0.5);
  EXPECT_EQ(c.values.at("--plan"), "x.yaml");
}

TEST(CommandLine, HelpIsRecognised) {
  EXPECT_TRUE(parse({"--help"}).help);
  EXPECT_TRUE(parse({"-h"}).help);
}

// Each bad command line is rejected with a message naming the option.
TEST(CommandLine, RejectsBadInput) {
  const std::vector<std::pair<std::vector<const char*>, std::string>> cases = {
      {{"--mode", "fast"}, "--mode"},
      {{"--prefix", "lower_"}, "--prefix"},
      {{"--max-steps", "-1"}, "--max-steps"},
      {{"--max-steps", "3.5"}, "--max-steps"},
      {{"--max-steps", ""}, "--max-steps"},
      {{"--timeout-s", "0"}, "--timeout-s"},
      {{"--timeout-s", "nan"}, "--timeout-s"},
      {{"--timeout-s", "1e9"}, "--timeout-s"},
      {{"--timeout-s"}, "--timeout-s needs a value"},
      {{"--unknown", "1"}, "unknown option '--unknown'"},
      {{"stray"}, "unexpected argument 'stray'"},
      {{"--lcm-url="}, "--lcm-url"},
  };
  for (const auto& [args, expected] : cases) {
    try {
      parse(args);
      ADD_FAILURE() << "accepted: " << expected;
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

TEST(CommandLine, ParseNumberAcceptsWholeNumbersOnly) {
  EXPECT_EQ(parse_number("--delay-ms", "12.5"), 12.5);
  EXPECT_THROW(parse_number("--delay-ms", "12ms"), UsageError);
  EXPECT_THROW(parse_number("--delay-ms", "inf"), UsageError);
  EXPECT_THROW(parse_number("--delay-ms", ""), UsageError);
}

}  // namespace
}  // namespace tongue::controller
