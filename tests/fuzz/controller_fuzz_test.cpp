// ep_controller under forged server messages on a real loopback bus, the test playing the server:
// a forged state with a status string of length 0 (lcm-gen's decoder threw on it: exit 1),
// truncations, absurd counts and lengths and random bytes on the state, model and rejection
// channels, a model with other muscles, a notice about another sender's activation, non-finite
// values, and raw datagrams in LCM's fragment format (the pair that crashes liblcm 1.3.1, 256 MB
// claims). The controller must survive each, report the rejections, and go on answering the real
// states. Built twice like server_fuzz_test.cpp (udpm ports 7939-7940 quick, 7959-7960 soak).
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "builtin_tongue_muscles.hpp"
#include "bus/channels.hpp"
#include "bus/messages.hpp"
#include "bus/wire_bytes.hpp"
#include "fuzz_support.hpp"
#include "support/lcm_datagrams.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef EP_CONTROLLER_PATH
#error "EP_CONTROLLER_PATH must name the ep_controller executable"
#endif
#ifndef LUA_STEP_CONTROLLER_PATH
#error "LUA_STEP_CONTROLLER_PATH must name the Lua controller's wrapper"
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
using tongue_lcm::lcmt_tongue_activation;
using tongue_lcm::lcmt_tongue_command;
using tongue_lcm::lcmt_tongue_model;
using tongue_lcm::lcmt_tongue_rejection;
using tongue_lcm::lcmt_tongue_state;

constexpr int kScale = FUZZ_SCALE;
constexpr int kPort = FUZZ_PORT + 7;
constexpr int kWaitMs = 30000;  // generous: the test must pass next to a CPU hog

lcmt_tongue_model tongue_model() {
  const testing::MuscleList muscles = testing::builtin_tongue_muscles();
  lcmt_tongue_model m{};
  m.num_nodes = 1;
  m.num_rest_positions = 3;
  m.rest_positions = {0.0, 0.0, 0.0};
  m.num_muscles = static_cast<std::int32_t>(muscles.names.size());
  m.muscle_names = muscles.names;
  m.muscle_max_forces = muscles.max_forces_n;
  m.dt = 0.004;
  return m;
}

lcmt_tongue_state state(std::int64_t step, std::size_t muscles) {
  lcmt_tongue_state s{};
  s.step = step;
  s.time = 0.004 * static_cast<double>(step);
  s.num_muscles = static_cast<std::int32_t>(muscles);
  s.muscle_lengths.assign(muscles, 0.03);
  s.muscle_velocities.assign(muscles, 0.0);
  s.activations.assign(muscles, 0.0);
  s.converged = true;
  s.status = "ok";
  return s;
}

// The test's side: the server's channels, raw.
class FakeServer {
 public:
  explicit FakeServer(const std::string& url) : lcm_(url) {
    lcm_.subscribeFunction(channels_.activation, &FakeServer::on_activation, this);
    lcm_.subscribeFunction(channels_.command, &FakeServer::on_command, this);
  }
  const bus::Channels& channels() const { return channels_; }
  void publish(const std::string& channel, const Bytes& b) {
    lcm_.publish(channel, b.data(), static_cast<unsigned>(b.size()));
  }
  // Handles messages until done() or timeout_ms; whether done() came true.
  template <typename Done>
  bool wait(Done done, int timeout_ms = kWaitMs) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (!done()) {
      if (std::chrono::steady_clock::now() > end) return false;
      lcm_.handleTimeout(50);
    }
    return true;
  }
  std::deque<std::int64_t> activation_steps;
  int describes = 0;

 private:
  static void on_activation(const lcm::ReceiveBuffer* rbuf, const std::string&, FakeServer* s) {
    lcmt_tongue_activation msg;
    if (msg.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) > 0)
      s->activation_steps.push_back(msg.step);
  }
  static void on_command(const lcm::ReceiveBuffer* rbuf, const std::string&, FakeServer* s) {
    lcmt_tongue_command msg;
    if (msg.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) > 0 &&
        msg.command == "describe")
      ++s->describes;
  }
  lcm::LCM lcm_;
  bus::Channels channels_;
};

// Whether the controller, stepped to 0 before, answers a later state: the states of steps 1, 2,
// ... are sent 200 ms apart until an activation for step 2 or later comes back. While the
// forgeries still fill the sockets' buffers the kernel drops datagrams that do not fit, the
// controller's answer (sent once per step) or the state itself; a new step gets a new answer.
bool answers_a_new_state(FakeServer& server, std::size_t muscles) {
  std::int64_t step = 0;
  auto last = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  return server.wait([&] {
    if (!server.activation_steps.empty() && server.activation_steps.back() >= 2) return true;
    if (std::chrono::steady_clock::now() - last > std::chrono::milliseconds(200)) {
      server.publish(server.channels().state, bus::testing::encoded(state(++step, muscles)));
      last = std::chrono::steady_clock::now();
    }
    return false;
  });
}

// Rejection notices no controller here sent: first a whole one about another sender's
// activation (shown once, not fatal), then one with a sender length of 0, its truncations,
// absurd int32s, random bytes after the fingerprint, and one over the channel's 8 kB limit.
std::vector<Bytes> forged_notices(std::mt19937& random) {
  lcmt_tongue_rejection notice{};
  notice.sender = "ep_controller:1";
  notice.activation_step = 1;
  notice.kind = "second activation";
  notice.reason = "forged";
  const Bytes whole = bus::testing::encoded(notice);
  Bytes zero_sender = whole;
  bus::testing::put_int32(zero_sender, 8 + 8 + 8, 0);  // after fingerprint, utime, step
  std::vector<Bytes> notices{whole, zero_sender};
  for (const auto& list : {testing::truncations(whole), testing::absurd_int32s(whole),
                           testing::random_after_fingerprint(whole, random, 500 * kScale)})
    notices.insert(notices.end(), list.begin(), list.end());
  notice.reason = std::string(20000, 'r');
  notices.push_back(bus::testing::encoded(notice));
  return notices;
}

class ControllerFuzz : public testing::TempDirTest {};

TEST_F(ControllerFuzz, EpControllerSurvivesForgedStatesAndModels) {
  const std::string url = testing::bus_url(kPort, 4194304);
  FakeServer server(url);
  testing::ChildProcess controller(EP_CONTROLLER_PATH,
                                   {"--plan", write("plan.yaml", "delta_lambda_mm: {SG: [0]}"),
                                    "--lcm-url", url, "--timeout-s", "600"},
                                   dir_, "ep");
  // The controller asks for the model; the test answers, then steps it once.
  ASSERT_TRUE(server.wait([&] { return server.describes > 0; })) << controller.stderr_text();
  const lcmt_tongue_model model = tongue_model();
  const std::size_t n = model.muscle_names.size();
  server.publish(server.channels().model, bus::testing::encoded(model));
  server.publish(server.channels().state, bus::testing::encoded(state(0, n)));
  ASSERT_TRUE(server.wait([&] { return !server.activation_steps.empty(); }))
      << controller.stderr_text();
  EXPECT_EQ(server.activation_steps.back(), 1);

  // The forged state of the report: status of length 0.
  Bytes zero_status = bus::testing::encoded(state(1, n));
  bus::testing::put_int32(zero_status, zero_status.size() - 8 - 8 - (4 + 3), 0);
  std::vector<Bytes> states{zero_status};
  // Variants of a state with one muscle too many: those that still decode are rejected for it.
  const Bytes wrong = bus::testing::encoded(state(1, n + 1));
  std::mt19937 random(7);
  for (const auto& list : {testing::truncations(wrong), testing::absurd_int32s(wrong)})
    states.insert(states.end(), list.begin(), list.end());
  for (int round = 0; round < kScale; ++round) {
    const auto r = testing::random_after_fingerprint(wrong, random, 2000);
    states.insert(states.end(), r.begin(), r.end());
  }
  lcmt_tongue_state not_finite = state(1, n);
  not_finite.muscle_lengths[0] = std::numeric_limits<double>::quiet_NaN();
  states.push_back(bus::testing::encoded(not_finite));
  lcmt_tongue_model other = model;
  other.muscle_names[0] = "XX";
  std::vector<Bytes> models{bus::testing::encoded(other)};
  const Bytes model_bytes = bus::testing::encoded(model);
  for (const auto& list : {testing::truncations(model_bytes), testing::absurd_int32s(model_bytes),
                           testing::random_after_fingerprint(model_bytes, random, 500 * kScale)})
    models.insert(models.end(), list.begin(), list.end());
  const std::vector<Bytes> notices = forged_notices(random);
  for (const Bytes& b : notices) server.publish(server.channels().rejection, b);
  for (const Bytes& b : states) server.publish(server.channels().state, b);
  for (const Bytes& b : models) server.publish(server.channels().model, b);
  testing::DatagramSender sender(kPort);
  const int claims = 500 * kScale;
  for (int i = 0; i < claims; ++i) {
    sender.send(testing::huge_claim(i, i % 2 ? server.channels().state : server.channels().model));
    for (const auto& d : testing::overflowing_fragments(100000 + i, server.channels().state))
      sender.send(d);
  }
  std::printf(
      "forged at ep_controller: %zu notices, %zu states, %zu models, %d claims of 2^28 bytes, %d "
      "overflowing fragment pairs sent\n",
      notices.size(), states.size(), models.size(), claims, claims);

  // Still answering: the real state of step 1 gets the activation for step 2.
  ASSERT_TRUE(controller.wait_stderr("rejected undecodable state", kWaitMs))
      << controller.stderr_text();
  const auto peak_kb = testing::peak_rss_kb(controller.pid());
  ASSERT_TRUE(answers_a_new_state(server, n)) << controller.stderr_text();
  EXPECT_TRUE(controller.running());
  std::printf("ep_controller peak RSS %ld kB\n", peak_kb);
  EXPECT_LT(peak_kb, 100 * 1024);  // kB; liblcm's reassembly would hold 256 MB per claim
  controller.signal(SIGTERM);
  EXPECT_EQ(controller.wait_exit(kWaitMs), 130) << controller.stderr_text();
  const std::string err = controller.stderr_text();
  EXPECT_NE(err.find("messages rejected"), std::string::npos) << err;
  EXPECT_NE(err.find("dropped oversize message"), std::string::npos) << err;
  EXPECT_NE(err.find("rejected model"), std::string::npos) << err;
  EXPECT_NE(err.find("rejected undecodable rejection notice"), std::string::npos) << err;
  EXPECT_NE(err.find("the server rejected an activation of \"ep_controller:1\""), std::string::npos)
      << err;
}

// The Lua controller receives through liblcm's own Lua module (its fragment reassembly is
// liblcm's: docs/security.md), so only forged messages are sent to it here: each is rejected
// and counted (or, a notice about another sender, ignored), and it goes on answering.
TEST_F(ControllerFuzz, LuaControllerSurvivesForgedStatesAndModels) {
  const std::string url = testing::bus_url(kPort + 1, 4194304);
  FakeServer server(url);
  testing::ChildProcess controller(LUA_STEP_CONTROLLER_PATH,
                                   {"--lcm-url", url, "--timeout-ms", "600000", "SL=0.1"}, dir_,
                                   "lua");
  ASSERT_TRUE(server.wait([&] { return server.describes > 0; })) << controller.stderr_text();
  const lcmt_tongue_model model = tongue_model();
  const std::size_t n = model.muscle_names.size();
  server.publish(server.channels().model, bus::testing::encoded(model));
  server.publish(server.channels().state, bus::testing::encoded(state(0, n)));
  ASSERT_TRUE(server.wait([&] { return !server.activation_steps.empty(); }))
      << controller.stderr_text();
  Bytes zero_status = bus::testing::encoded(state(1, n));
  bus::testing::put_int32(zero_status, zero_status.size() - 8 - 8 - (4 + 3), 0);
  std::mt19937 random(8);
  std::vector<Bytes> states{zero_status};
  const Bytes wrong = bus::testing::encoded(state(1, n + 1));
  for (const auto& list : {testing::truncations(wrong),
                           testing::random_after_fingerprint(wrong, random, 500 * kScale)})
    states.insert(states.end(), list.begin(), list.end());
  std::vector<Bytes> models =
      testing::random_after_fingerprint(bus::testing::encoded(model), random, 500 * kScale);
  const std::vector<Bytes> notices = forged_notices(random);
  for (const Bytes& b : notices) server.publish(server.channels().rejection, b);
  for (const Bytes& b : states) server.publish(server.channels().state, b);
  for (const Bytes& b : models) server.publish(server.channels().model, b);
  std::printf("forged at the Lua controller: %zu notices, %zu states, %zu models sent\n",
              notices.size(), states.size(), models.size());
  ASSERT_TRUE(controller.wait_stderr("rejected", kWaitMs)) << controller.stderr_text();
  const std::size_t answered = server.activation_steps.size();
  ASSERT_TRUE(answers_a_new_state(server, n)) << controller.stderr_text();
  EXPECT_GT(server.activation_steps.size(), answered);
  EXPECT_TRUE(controller.running()) << controller.stderr_text();
}

}  // namespace
}  // namespace tongue::fuzz
