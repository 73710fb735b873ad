// Two sim_server processes at once, each on its own port and channel prefix and driven by its own
// controller thread with its own activations: each run file equals, bit for bit, the one the same
// server and controller produce alone, and a listener on each bus (every channel) hears only its
// own server's channels. Ports 7840 and 7841 (alone), 7842 and 7843 (together).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/messages.hpp"
#include "support/same_run.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif

namespace tongue::server {
namespace {

namespace fs = std::filesystem;
using testing::bus_url;
using testing::ChildProcess;
using testing::ServerController;

constexpr int kSteps = 15;
constexpr int kExitWaitMs = 5000;

// One experiment: a scene, a channel prefix and the activation its controller sends for step k.
struct Experiment {
  std::string name;
  const char* scene;
  std::string prefix;
  std::function<void(ServerController&, int)> send;
};

const Experiment kFirst{"first", testing::kBoxScene, "TONGUE_A_", [](ServerController& c, int k) {
                          c.send_activation(k, {"flexor"}, {0.1 + 0.08 * (k % 5)});
                        }};
const Experiment kSecond{
    "second", testing::kTwoMuscleBoxScene, "TONGUE_B_", [](ServerController& c, int k) {
      c.send_activation(k, {"flexor", "extensor"}, {0.9 - 0.05 * k, k >= 4 ? 0.3 : 0.0});
    }};

// Counts the messages of every channel on one bus, and the steps of the states, from its own
// thread.
class BusListener {
 public:
  explicit BusListener(const std::string& url) : lcm_(url) {
    // LCM's default queue holds 30 messages per subscription and drops the rest: a listener
    // thread short of CPU on a loaded machine would miss the last of a run's 33 or more.
    if (lcm_.good()) lcm_.subscribe(".*", &BusListener::on_message, this)->setQueueCapacity(100000);
    thread_ = std::thread([this] {
      while (!stop_) lcm_.handleTimeout(20);
    });
  }
  ~BusListener() { stop(); }
  BusListener(const BusListener&) = delete;
  BusListener& operator=(const BusListener&) = delete;

  bool good() { return lcm_.good(); }
  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  std::map<std::string, int> counts() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
  }
  // The distinct steps of the states heard, in order.
  std::set<std::int64_t> state_steps() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return state_steps_;
  }
  // Whether a message on channel has been counted within timeout_ms (polled).
  bool wait_for(const std::string& channel, int timeout_ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (counts()[channel] == 0) {
      if (std::chrono::steady_clock::now() > end) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return true;
  }

 private:
  void on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++counts_[channel];
    tongue_lcm::lcmt_tongue_state state;
    const bool is_state =
        channel.size() >= 5 && channel.compare(channel.size() - 5, 5, "STATE") == 0;
    if (is_state && state.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) > 0)
      state_steps_.insert(state.step);
  }

  lcm::LCM lcm_;
  std::mutex mutex_;
  std::map<std::string, int> counts_;
  std::set<std::int64_t> state_steps_;
  std::atomic<bool> stop_{false};
  std::thread thread_;  // last: started once everything it uses exists
};

class TwoServers : public testing::TempDirTest {
 protected:
  // Starts the experiment's server on url with the run file <name>_<tag>.h5.
  std::unique_ptr<ChildProcess> start(const Experiment& e, const std::string& url,
                                      const std::string& tag) {
    const std::string run = e.name + "_" + tag;
    return std::make_unique<ChildProcess>(
        SIM_SERVER_PATH,
        std::vector<std::string>{write(e.name + ".yaml", e.scene), "--lcm-url", url, "--prefix",
                                 e.prefix, "--output", (dir_ / (run + ".h5")).string()},
        dir_, run);
  }
};

// Drives one server through kSteps in lock-step, then shuts it down. Returns what went wrong, or
// an empty text.
std::string drive(const Experiment& e, ServerController& controller, ChildProcess& server) {
  for (int k = 0; k < kSteps; ++k) {
    if (!controller.wait_step(k)) return e.name + ": no state for step " + std::to_string(k);
    e.send(controller, k + 1);
  }
  const auto last = controller.wait_step(kSteps);
  if (!last) return e.name + ": no state for the last step";
  if (last->rejected_messages != 0)
    return e.name + ": " + std::to_string(last->rejected_messages) + " messages rejected";
  controller.send_command("shutdown");
  const auto status = server.wait_exit(kExitWaitMs);
  if (status != 0) return e.name + ": exit status " + std::to_string(status.value_or(-1));
  return "";
}

TEST_F(TwoServers, RunAtOnceWithoutCrosstalk) {
  // Each alone.
  int port = 7840;
  for (const Experiment* e : {&kFirst, &kSecond}) {
    const std::string url = bus_url(port++);
    ServerController controller(url, e->prefix);
    ASSERT_TRUE(controller.good());
    auto server = start(*e, url, "alone");
    ASSERT_TRUE(server->started());
    const std::string error = drive(*e, controller, *server);
    ASSERT_EQ(error, "") << server->stderr_text();
  }

  // Both at once, each on its own port, with a listener on every channel of each bus.
  const std::string url_first = bus_url(7842), url_second = bus_url(7843);
  BusListener bus_first(url_first), bus_second(url_second);
  ASSERT_TRUE(bus_first.good() && bus_second.good());
  ServerController first(url_first, kFirst.prefix), second(url_second, kSecond.prefix);
  ASSERT_TRUE(first.good() && second.good());
  auto server_first = start(kFirst, url_first, "together");
  auto server_second = start(kSecond, url_second, "together");
  ASSERT_TRUE(server_first->started() && server_second->started());
  std::string error_first, error_second;
  std::thread t1([&] { error_first = drive(kFirst, first, *server_first); });
  std::thread t2([&] { error_second = drive(kSecond, second, *server_second); });
  t1.join();
  t2.join();
  EXPECT_EQ(error_first, "") << server_first->stderr_text();
  EXPECT_EQ(error_second, "") << server_second->stderr_text();
  // The shutdown is the last message of each bus; a listener thread short of CPU may still be
  // handling what came before it. A little more time after it, for anything straying in late.
  EXPECT_TRUE(bus_first.wait_for(kFirst.prefix + "COMMAND", kExitWaitMs));
  EXPECT_TRUE(bus_second.wait_for(kSecond.prefix + "COMMAND", kExitWaitMs));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  bus_first.stop();
  bus_second.stop();

  for (const Experiment* e : {&kFirst, &kSecond}) {
    testing::expect_same_results(dir_ / (e->name + "_alone.h5"), dir_ / (e->name + "_together.h5"),
                                 kSteps + 1);
  }
  // Each bus carried exactly its own server's traffic: the model once, the states of steps 0 to
  // kSteps, kSteps activations and the shutdown; besides, LCM_SELF_TEST, which every udpm LCM
  // instance sends to itself when it starts receiving (LCM's check that multicast loops back).
  // A state may come more than once: the server publishes it again when the test's controller
  // thread, short of CPU, answers it late.
  const std::vector<std::pair<const Experiment*, BusListener*>> buses{{&kFirst, &bus_first},
                                                                      {&kSecond, &bus_second}};
  std::set<std::int64_t> all_steps;
  for (std::int64_t k = 0; k <= kSteps; ++k) all_steps.insert(k);
  for (const auto& [e, bus] : buses) {
    std::map<std::string, int> counts = bus->counts();
    counts.erase("LCM_SELF_TEST");
    EXPECT_GE(counts[e->prefix + "STATE"], kSteps + 1) << e->name << "'s bus";
    EXPECT_EQ(bus->state_steps(), all_steps) << e->name << "'s bus";
    counts.erase(e->prefix + "STATE");
    const std::map<std::string, int> expected{
        {e->prefix + "ACTIVATION", kSteps}, {e->prefix + "COMMAND", 1}, {e->prefix + "MODEL", 1}};
    EXPECT_EQ(counts, expected) << e->name << "'s bus";
  }
}

}  // namespace
}  // namespace tongue::server
