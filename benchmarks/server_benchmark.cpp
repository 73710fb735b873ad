// End-to-end figures of sim_server on a real LCM bus (udpm on the loopback), this program acting
// as the controller:
//  1. Lock-step round trip on a small box (one muscle) and on the built-in tongue (refinement 1):
//     time from sending the activation for step k + 1 to receiving the state of k + 1, the
//     server's own step_wall_time (from that state), and their difference, the lock-step
//     overhead beyond the physics (encode, udpm both ways, decode, publishing, logging).
//  2. The activation rate the server absorbs in fast mode (box). The server does not publish
//     how many activations it accepted, and a dropped datagram leaves no trace, so the method
//     is: at each rate R (1k, 5k, 20k, 50k msg/s, 1 s each), send pairs of messages with step
//     -1: a valid one (the muscle at level 0, the level the server starts
//     with, so that the physics, hence Newton's work per step, does not change) and, right after
//     it, an invalid twin (an unknown muscle name) the server rejects and counts in
//     rejected_messages. Both take the same path (same channel, same size class), so the fraction
//     of twins counted is the fraction of all messages delivered. Meanwhile the state stream's step
//     rate is compared with the rate without activations: the server keeps up when delivery is ~100
//     % and the step rate does not drop (the server reads the bus between steps, so absorbing
//     messages costs step rate). The sustainable rate is the highest R with delivery >= 99.9 % and
//     step rate >= 90 % of the one with the same sending loop sending nothing.
//  3. Run file size per simulated second for the tongue (every step logged, all nodes).
//
// Usage: server_benchmark [--box-steps N] [--tongue-steps N]   (defaults 200 and 50)
// Uses ports 7790-7792. Build in Release; it takes well under 2 minutes.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/channels.hpp"
#include "bus/messages.hpp"
#include "median.hpp"
#include "support/sim_server_driver.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using tongue_lcm::lcmt_tongue_activation;
using tongue_lcm::lcmt_tongue_state;

// scenes/tongue_sg_3n.yaml without its activation schedule and output (the benchmark drives it).
const char* const kTongueScene = R"(
mesh:
  tongue: {refinement: 1}
material:
  type: mooney_rivlin5
  parameters: {poisson_ratio: 0.49}
  density: 1000
constraints:
  - {set: mandible, components: [x, y, z]}
  - {set: root_bottom, components: [y]}
  - {set: hyoid, components: [y, z]}
gravity: [0, -9.81, 0]
damping: {alpha: 0.0, beta: 0.028}
muscles: builtin
analysis:
  type: dynamic
  settle: true
  duration: 0.12
  dt: 0.004
)";

using tongue::benchmarks::median;
using tongue::testing::bus_url;
using tongue::testing::ChildProcess;
using tongue::testing::kBoxScene;
using tongue::testing::ServerController;

constexpr int kModelWaitMs = 30000;  // longest wait for the model (the tongue's takes a while)
constexpr int kStepWaitMs = 20000;   // longest wait for one state

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// sim_server started with args (stdout and stderr to files in dir); throws when it cannot start.
std::unique_ptr<ChildProcess> start_server(const std::vector<std::string>& args,
                                           const fs::path& dir) {
  auto server = std::make_unique<ChildProcess>(SIM_SERVER_PATH, args, dir);
  if (!server->started()) throw std::runtime_error("cannot start " + std::string(SIM_SERVER_PATH));
  return server;
}

double mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

struct LockStepFigures {
  std::string name;
  int steps = 0;
  std::vector<double> rtt_us, physics_us, overhead_us;
  double dt = 0.0;  // s
  std::uintmax_t run_file_bytes = 0;
};

// Drives a lock-step server through steps steps, muscle muscle (the model's first) at a level
// ramping in [0.1, 0.3].
LockStepFigures lock_step(const std::string& name, const char* scene, int port, int steps,
                          const fs::path& dir) {
  LockStepFigures f;
  f.name = name;
  f.steps = steps;
  const fs::path scene_file = dir / (name + ".yaml");
  std::ofstream(scene_file) << scene;
  const fs::path run_file = dir / (name + ".h5");
  const std::string url = bus_url(port);
  ServerController c(url);
  if (!c.good()) throw std::runtime_error("cannot open the LCM bus at " + url);
  const auto server =
      start_server({scene_file.string(), "--lcm-url", url, "--output", run_file.string()}, dir);
  const auto model = c.wait_model(kModelWaitMs);
  if (!model || model->muscle_names.empty())
    throw std::runtime_error(name + ": no model from the server (see " + dir.string() + ")");
  f.dt = model->dt;
  if (!c.wait_step(0, kStepWaitMs)) throw std::runtime_error(name + ": no state 0");
  const std::string muscle = model->muscle_names.front();
  for (int k = 1; k <= steps; ++k) {
    const auto t0 = Clock::now();
    c.send_activation(k, {muscle}, {0.1 + 0.2 * k / steps});
    const auto s = c.wait_step(k, kStepWaitMs);
    const double rtt = seconds_since(t0) * 1e6;
    if (!s) throw std::runtime_error(name + ": no state for step " + std::to_string(k));
    f.rtt_us.push_back(rtt);
    f.physics_us.push_back(s->step_wall_time * 1e6);
    f.overhead_us.push_back(rtt - s->step_wall_time * 1e6);
  }
  c.send_command("shutdown");
  if (server->wait_exit(10000) != 0) throw std::runtime_error(name + ": server did not exit 0");
  f.run_file_bytes = fs::file_size(run_file);
  return f;
}

struct RateFigures {
  int rate = 0;           // msg/s asked
  long long sent = 0;     // messages sent (valid + invalid twins)
  long long counted = 0;  // invalid twins the server counted
  double delivered = 0;   // fraction
  double step_rate = 0;   // server steps/s during the window
};

// The state stream of a fast-mode server, read on its own thread: latest step and rejection
// count, and the step at given moments.
class StateWatcher {
 public:
  explicit StateWatcher(const std::string& url) : lcm_(url) {
    if (!lcm_.good()) throw std::runtime_error("cannot open the LCM bus at " + url);
    lcm_.subscribe(tongue::bus::Channels().state, &StateWatcher::on_state, this);
    thread_ = std::thread([this] {
      while (!stop_) lcm_.handleTimeout(50);
    });
  }
  ~StateWatcher() {
    stop_ = true;
    thread_.join();
  }
  StateWatcher(const StateWatcher&) = delete;
  StateWatcher& operator=(const StateWatcher&) = delete;
  std::int64_t step() const { return step_; }
  std::int64_t rejected() const { return rejected_; }

 private:
  void on_state(const lcm::ReceiveBuffer*, const std::string&, const lcmt_tongue_state* s) {
    step_ = s->step;
    rejected_ = s->rejected_messages;
  }
  lcm::LCM lcm_;
  std::atomic<bool> stop_{false};
  std::atomic<std::int64_t> step_{-1}, rejected_{0};
  std::thread thread_;
};

// Fast mode on the box: step rate idle, then under pairs of activations at each rate.
std::pair<double, std::vector<RateFigures>> fast_mode_rates(int port, const fs::path& dir) {
  const fs::path scene_file = dir / "fast_box.yaml";
  std::ofstream(scene_file) << kBoxScene;
  const std::string url = bus_url(port);
  StateWatcher watch(url);
  // States every 10 steps: the watcher must not be the bottleneck. No run file: logging is not
  // what is measured here.
  const auto server = start_server(
      {scene_file.string(), "--lcm-url", url, "--mode", "fast", "--publish-every", "10"}, dir);
  lcm::LCM out(url);
  const std::string channel = tongue::bus::Channels().activation;
  const auto wait_started = Clock::now();
  while (watch.step() < 100) {
    if (seconds_since(wait_started) > 20) throw std::runtime_error("fast server did not start");
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  auto step_rate_over = [&](double seconds, const std::function<void(double)>& during) {
    const std::int64_t s0 = watch.step();
    const auto t0 = Clock::now();
    during(seconds);
    return static_cast<double>(watch.step() - s0) / seconds_since(t0);
  };

  lcmt_tongue_activation valid;
  valid.utime = 0;
  valid.step = -1;
  valid.num_muscles = 1;
  valid.names = {"flexor"};
  valid.levels = {0.0};
  lcmt_tongue_activation twin = valid;
  twin.names = {"flexer"};  // unknown: rejected and counted

  // Rate 0 first: the same sending loop (it wakes every 200 us) with nothing to send, the
  // baseline step rate on this machine with the benchmark's threads competing for the cores.
  std::vector<RateFigures> figures;
  double idle = 0.0;
  for (const int rate : {0, 1000, 5000, 20000, 50000}) {
    RateFigures r;
    r.rate = rate;
    const std::int64_t rejected0 = watch.rejected();
    long long pairs = 0;
    r.step_rate = step_rate_over(1.0, [&](double seconds) {
      const auto t0 = Clock::now();
      while (true) {
        const double t = seconds_since(t0);
        if (t >= seconds) break;
        // Every message due by now (a pair is two messages), then a short sleep.
        const auto due = static_cast<long long>(t * rate / 2.0);
        for (; pairs < due; ++pairs) {
          out.publish(channel, &valid);
          out.publish(channel, &twin);
        }
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    });
    // Let the server drain and publish (every 10 steps) a state with the final count.
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    r.sent = 2 * pairs;
    r.counted = watch.rejected() - rejected0;
    r.delivered = pairs > 0 ? static_cast<double>(r.counted) / static_cast<double>(pairs) : 0.0;
    if (rate == 0) {
      idle = r.step_rate;
    } else {
      figures.push_back(r);
    }
  }
  tongue_lcm::lcmt_tongue_command shutdown;
  shutdown.utime = 0;
  shutdown.command = "shutdown";
  out.publish(tongue::bus::Channels().command, &shutdown);
  server->wait_exit(5000);
  return {idle, figures};
}

}  // namespace

int main(int argc, char** argv) {
  int box_steps = 200, tongue_steps = 50;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--box-steps") {
      box_steps = std::atoi(argv[i + 1]);
    } else if (a == "--tongue-steps") {
      tongue_steps = std::atoi(argv[i + 1]);
    } else {
      std::fprintf(stderr, "usage: server_benchmark [--box-steps N] [--tongue-steps N]\n");
      return 1;
    }
  }
  const fs::path dir =
      fs::temp_directory_path() / ("server_benchmark_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto start = Clock::now();
  try {
    std::vector<LockStepFigures> runs;
    runs.push_back(lock_step("box", kBoxScene, 7790, box_steps, dir));
    runs.push_back(lock_step("tongue", kTongueScene, 7791, tongue_steps, dir));
    const auto [idle, rates] = fast_mode_rates(7792, dir);

    std::printf("sim_server, lock-step round trip (activation sent -> state received)\n");
    std::printf("%-7s %6s | %10s %10s | %10s %10s | %10s %10s\n", "scene", "steps", "rtt mean",
                "rtt med", "phys mean", "phys med", "ovh mean", "ovh med");
    std::printf("%-7s %6s | %10s %10s | %10s %10s | %10s %10s\n", "", "", "[us]", "[us]", "[us]",
                "[us]", "[us]", "[us]");
    for (const LockStepFigures& f : runs)
      std::printf("%-7s %6d | %10.0f %10.0f | %10.0f %10.0f | %10.0f %10.0f\n", f.name.c_str(),
                  f.steps, mean(f.rtt_us), median(f.rtt_us), mean(f.physics_us),
                  median(f.physics_us), mean(f.overhead_us), median(f.overhead_us));
    std::printf("(phys: the state's step_wall_time; ovh: rtt - phys, the lock-step overhead)\n\n");

    std::printf(
        "fast mode, box, activations with step -1 (half valid, half counted invalid "
        "twins)\n");
    std::printf("step rate with nothing sent: %.0f steps/s\n", idle);
    std::printf("%10s %10s %10s %10s %12s\n", "rate", "sent", "delivered", "delivered",
                "step rate");
    std::printf("%10s %10s %10s %10s %12s\n", "[msg/s]", "[msg]", "[msg]", "[%]", "[steps/s]");
    int sustained = 0;
    for (const RateFigures& r : rates) {
      std::printf("%10d %10lld %10lld %10.2f %12.0f\n", r.rate, r.sent, 2 * r.counted,
                  100.0 * r.delivered, r.step_rate);
      if (r.delivered >= 0.999 && r.step_rate >= 0.9 * idle) sustained = r.rate;
    }
    std::printf(
        "highest rate absorbed (delivered >= 99.9 %%, step rate >= 90 %% of that): "
        "%d msg/s%s\n\n",
        sustained, sustained == 0 ? " (none)" : "");

    const LockStepFigures& t = runs[1];
    const double simulated = t.steps * t.dt;
    std::printf(
        "tongue run file: %ju bytes for %d steps of %g s = %g s simulated (step 0 "
        "frame and header included): %.0f kB per simulated second\n",
        t.run_file_bytes, t.steps, t.dt, simulated,
        static_cast<double>(t.run_file_bytes) / simulated / 1e3);
    std::printf("total benchmark time: %.1f s\n", seconds_since(start));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "server_benchmark: %s (server output in %s)\n", e.what(),
                 dir.string().c_str());
    return 1;
  }
  fs::remove_all(dir);
  return 0;
}
