// sim_server under a hostile client on a real loopback bus: random bytes, truncations and absurd
// counts and lengths on both channels it receives on (activation, command), raw datagrams in
// LCM's fragment format (the pair that crashes liblcm 1.3.1, 256 MB claims, random fragments),
// floods and a command storm. After each scenario the server must still be alive and correct:
// it answers "describe" with its model, steps on a valid activation, and exits 0 on "shutdown".
// Built twice: quick for CI (label integration, FUZZ_SCALE 1, udpm ports 7932-7938) and a soak
// (label slow, FUZZ_SCALE 50, ports 7952-7958). Each scenario prints the counts it sent.
#include <gtest/gtest.h>

#include <signal.h>

#include <atomic>
#include <cstdio>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/command.hpp"
#include "bus/wire_bytes.hpp"
#include "fuzz_support.hpp"
#include "support/lcm_datagrams.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif
#ifndef FUZZ_SCALE
#define FUZZ_SCALE 1
#endif
#ifndef FUZZ_PORT
#define FUZZ_PORT 7932
#endif

namespace tongue::fuzz {
namespace {

using testing::Bytes;
using testing::ChildProcess;
using testing::DatagramSender;
using testing::ServerController;

constexpr int kScale = FUZZ_SCALE;
// Generous waits: the tests must pass next to a CPU hog on 2 cores.
constexpr int kWaitMs = 30000;
// Peak resident memory allowed to the server under any flood here [kB]: it starts at about
// 17 MB; liblcm's reassembly took it past 1 GB with five 256 MB claims.
constexpr long kPeakRssKb = 100 * 1024;

class ServerFuzz : public testing::TempDirTest {
 protected:
  // Starts the server on the box scene, port FUZZ_PORT + offset, and waits for its model.
  void start(int offset) {
    url_ = testing::bus_url(FUZZ_PORT + offset, 4194304);
    port_ = FUZZ_PORT + offset;
    listener_ = std::make_unique<ServerController>(url_);
    publisher_ = std::make_unique<lcm::LCM>(url_);
    server_ = std::make_unique<ChildProcess>(
        SIM_SERVER_PATH,
        std::vector<std::string>{write("box.yaml", testing::kBoxScene), "--lcm-url", url_,
                                 "--timeout-ms", "600000"},
        dir_);
    ASSERT_TRUE(listener_->wait_model(kWaitMs).has_value()) << server_->stderr_text();
    ASSERT_TRUE(listener_->wait_step(0, kWaitMs).has_value()) << server_->stderr_text();
  }

  void send_activation_bytes(const Bytes& b) {
    publisher_->publish(listener_->channels().activation, b.data(),
                        static_cast<unsigned>(b.size()));
  }
  void send_command_bytes(const Bytes& b) {
    publisher_->publish(listener_->channels().command, b.data(), static_cast<unsigned>(b.size()));
  }

  // The step of the server once it runs unpaused: "resume" and "describe" (model, then the
  // current state, "paused" or "ok") until a state says "ok". Repeated, because a datagram sent
  // while a flood still fills the server's socket buffer is dropped by the kernel (a storm's
  // last "pause" may have got through and the "resume" after it not).
  std::optional<std::int64_t> running_step() {
    for (int waited = 0; waited < kWaitMs; waited += 500) {
      listener_->send_command("resume");
      listener_->send_command("describe");
      std::optional<ServerController::State> last;
      while (auto s = listener_->wait_state([](const auto&) { return true; }, 500))
        last = std::move(s);
      if (last && last->status == "ok") return last->step;
    }
    return std::nullopt;
  }

  // The server is alive and correct: it describes itself, takes the next step from a valid
  // activation, and shuts down cleanly. (A hostile variant may itself be a valid activation that
  // stepped it: the current step is read from the answer.) The activation is sent again until
  // its step comes, for the same reason as in running_step (a repeat is stale: rejected).
  void expect_alive_then_shutdown() {
    ASSERT_TRUE(server_->running()) << server_->stderr_text();
    const std::optional<std::int64_t> step = running_step();
    ASSERT_TRUE(step.has_value()) << server_->stderr_text();
    EXPECT_TRUE(listener_->wait_model(kWaitMs).has_value()) << server_->stderr_text();
    std::optional<ServerController::State> state;
    for (int waited = 0; !state && waited < kWaitMs; waited += 500) {
      listener_->send_activation(*step + 1, {"flexor"}, {0.5});
      state = listener_->wait_step(*step + 1, 500);
    }
    ASSERT_TRUE(state.has_value()) << server_->stderr_text();
    EXPECT_TRUE(state->converged);
    EXPECT_EQ(state->activations, std::vector<double>{0.5});
    sample_rss();  // VmHWM: the peak since the server started
    EXPECT_GT(rss_kb_, 0);
    EXPECT_LT(rss_kb_, kPeakRssKb);
    EXPECT_EQ(shut_down_repeatedly(), 0) << server_->stderr_text();
  }

  // Sends "shutdown" every 200 ms until the server exits (a flood may fill its socket buffer,
  // where the kernel drops any datagram that does not fit, commands too); its exit status.
  std::optional<int> shut_down_repeatedly() {
    for (int waited = 0; waited < kWaitMs; waited += 200) {
      listener_->send_command("shutdown");
      if (const auto status = server_->wait_exit(200)) return status;
    }
    return std::nullopt;
  }

  // Samples the server's peak memory (while it runs).
  void sample_rss() {
    const long kb = testing::peak_rss_kb(server_->pid());
    if (kb > rss_kb_) rss_kb_ = kb;
  }

  std::string url_;
  int port_ = 0;
  long rss_kb_ = 0;
  std::unique_ptr<ServerController> listener_;
  std::unique_ptr<lcm::LCM> publisher_;
  std::unique_ptr<ChildProcess> server_;
};

// lcm-gen's decoder threw on a command string of length 0 or below (exit 1) and read out of
// bounds on INT32_MIN (SIGSEGV); random bytes after the fingerprint killed it within a few.
TEST_F(ServerFuzz, HostileCommandsAreRejected) {
  start(0);
  // Variants that leave the message whole (a changed utime) are harmless describes.
  const Bytes valid = bus::testing::encoded(bus::command_message(bus::Command::describe, 1));
  std::mt19937 random(1);
  std::vector<Bytes> hostile = testing::truncations(valid);
  const auto absurd = testing::absurd_int32s(valid);
  hostile.insert(hostile.end(), absurd.begin(), absurd.end());
  Bytes the43 = valid;  // the 43-byte message of the report: length 0, padding after
  the43.resize(43, 'x');
  for (int i = 16; i < 20; ++i) the43[i] = 0;
  hostile.push_back(the43);
  for (int round = 0; round < kScale; ++round) {
    const auto r = testing::random_after_fingerprint(valid, random, 2000);
    hostile.insert(hostile.end(), r.begin(), r.end());
  }
  for (const Bytes& b : hostile) send_command_bytes(b);
  std::printf("hostile commands: %zu sent\n", hostile.size());
  EXPECT_TRUE(server_->wait_stderr("rejected undecodable command", kWaitMs));
  expect_alive_then_shutdown();
}

TEST_F(ServerFuzz, HostileActivationsAreRejected) {
  start(1);
  // Tagged 5, a future step: no variant of it is an activation the server would step on (an
  // int32 written over the step's low word makes it stale or later still).
  const Bytes valid = bus::testing::encoded(ServerController::activation(5, {"flexor"}, {0.25}));
  std::mt19937 random(2);
  std::vector<Bytes> hostile = testing::truncations(valid);
  const auto absurd = testing::absurd_int32s(valid);
  hostile.insert(hostile.end(), absurd.begin(), absurd.end());
  for (int round = 0; round < kScale; ++round) {
    const auto r = testing::random_after_fingerprint(valid, random, 3000);
    hostile.insert(hostile.end(), r.begin(), r.end());
  }
  // Absurd counts with the bytes to back some of them: 10 000 names of one letter.
  const auto many = ServerController::activation(1, std::vector<std::string>(10000, "x"),
                                                 std::vector<double>(10000, 0.5));
  hostile.push_back(bus::testing::encoded(many));
  for (const Bytes& b : hostile) send_activation_bytes(b);
  std::printf("hostile activations: %zu sent\n", hostile.size());
  EXPECT_TRUE(server_->wait_stderr("rejected undecodable activation", kWaitMs));
  // The 10 000 names are past the activation limit (4 kB for one muscle): dropped unread.
  EXPECT_TRUE(server_->wait_stderr("dropped oversize message", kWaitMs)) << server_->stderr_text();
  expect_alive_then_shutdown();
}

// Raw datagrams below the message level, on the server's own port.
TEST_F(ServerFuzz, ForgedDatagramsAndFragmentsAreDropped) {
  start(2);
  DatagramSender sender(port_);
  ASSERT_TRUE(sender.good());
  std::mt19937 random(3);
  const std::string channel = listener_->channels().activation;
  int overflow = 0, claims = 0, garbage = 0, fragments = 0;
  for (int round = 0; round < kScale; ++round) {
    for (int i = 0; i < 100; ++i, ++overflow)
      for (const auto& d : testing::overflowing_fragments(10000 * round + i, channel))
        sender.send(d);
    for (int i = 0; i < 1000; ++i, ++claims) {
      sender.send(testing::huge_claim(20000 + i, i % 2 ? channel : listener_->channels().command));
      if (i % 100 == 0) sample_rss();
    }
    for (int i = 0; i < 2000; ++i, ++garbage)
      sender.send(testing::random_bytes(random, random() % 1500));
    for (int i = 0; i < 2000; ++i, ++fragments) {
      // A fragment header with random fields, half of them starting a message on the channel.
      const auto number = static_cast<std::uint16_t>(i % 2 ? 0 : random() % 4);
      sender.send(testing::fragment(random() % 8, random(), random(), number,
                                    static_cast<std::uint16_t>(random() % 5), number ? "" : channel,
                                    testing::random_bytes(random, random() % 200)));
    }
    sample_rss();
  }
  std::printf(
      "forged datagrams: %d overflowing fragment pairs, %d claims of 2^28 bytes, %d random "
      "datagrams, %d random fragments sent; server peak RSS %ld kB\n",
      overflow, claims, garbage, fragments, rss_kb_);
  EXPECT_TRUE(server_->wait_stderr("dropped", kWaitMs));
  expect_alive_then_shutdown();
}

// A flood of bad activations, then "shutdown": honoured while the flood is still being read.
TEST_F(ServerFuzz, ShutdownIsHonouredDuringAFlood) {
  start(3);
  const Bytes bad = testing::truncations(
      bus::testing::encoded(ServerController::activation(1, {"flexor"}, {0.25})))[20];
  std::atomic<bool> stop{false};
  std::atomic<int> sent{0};
  std::thread flood([&] {
    lcm::LCM lcm(url_);
    while (!stop) {
      lcm.publish(listener_->channels().activation, bad.data(), static_cast<unsigned>(bad.size()));
      ++sent;
    }
  });
  while (sent < 20000 * kScale) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const auto status = shut_down_repeatedly();
  stop = true;
  flood.join();
  std::printf("flood: %d bad activations sent before and during the shutdown\n", sent.load());
  EXPECT_EQ(status, 0) << server_->stderr_text();
}

TEST_F(ServerFuzz, SigtermIsHonouredDuringAFlood) {
  start(4);
  DatagramSender sender(port_);
  std::atomic<bool> stop{false};
  std::atomic<int> sent{0};
  std::thread flood([&] {
    const auto claim = testing::huge_claim(1, listener_->channels().activation);
    while (!stop) {
      sender.send(claim);
      ++sent;
    }
  });
  while (sent < 20000 * kScale) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  server_->signal(SIGTERM);
  const auto status = server_->wait_exit(kWaitMs);
  stop = true;
  flood.join();
  std::printf("flood: %d claims of 2^28 bytes sent before and during SIGTERM\n", sent.load());
  EXPECT_EQ(status, 130) << server_->stderr_text();
}

// Random commands, valid and not, some with control characters in their names: every one is
// handled (or rejected) and no report line can be forged by a name.
TEST_F(ServerFuzz, ACommandStormLeavesItCorrect) {
  start(5);
  std::mt19937 random(5);
  const std::string names[] = {
      "pause",   "resume", "describe", "reset", "shutdown\nsim_server: shutdown at step 99",
      "\x1b[2J", "resume "};
  const int count = 2000 * kScale;
  for (int i = 0; i < count; ++i) listener_->send_command(names[random() % 7]);
  listener_->send_command("resume");
  std::printf("command storm: %d commands sent\n", count + 1);
  EXPECT_TRUE(server_->wait_stderr("rejected unknown command", kWaitMs));
  expect_alive_then_shutdown();
  const std::string err = server_->stderr_text();
  EXPECT_EQ(err.find("\nsim_server: shutdown at step 99"), std::string::npos) << err;
}

// A name with a newline and a 1 MB-long one: reports stay one bounded line each.
TEST_F(ServerFuzz, ReportsEscapeAndCutReceivedNames) {
  start(6);
  // One report per kind per second: the second name after the first one's report and a second.
  listener_->send_activation(1, {"x\nsim_server: shutdown at step 99"}, {0.5});
  EXPECT_TRUE(server_->wait_stderr("x\\nsim_server: shutdown at step 99", kWaitMs))
      << server_->stderr_text();
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  listener_->send_activation(1, {std::string(3000, 'n')}, {0.5});
  EXPECT_TRUE(server_->wait_stderr("...(3000 bytes)", kWaitMs)) << server_->stderr_text();
  expect_alive_then_shutdown();
  const std::string err = server_->stderr_text();
  EXPECT_EQ(err.find("\nsim_server: shutdown at step 99"), std::string::npos) << err;
  EXPECT_EQ(err.find(std::string(100, 'n')), std::string::npos);
}

}  // namespace
}  // namespace tongue::fuzz
