#pragma once
// The live side of the viewer: a thread of its own on the bus, watching one sim_server as a
// passive controller would (controller::ControllerBus: every message checked, a state against
// its model), never sending an activation. It asks for the model with "describe" until one comes
// (so a viewer may join late), keeps only the newest state, and hands what changed to a callback
// (called on the feed's thread; it must not block). If the bus fails, the thread says why (on
// stderr and to the sink) and ends; the pages keep what they have.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "viewer/drawing_model.hpp"
#include "viewer/frame.hpp"

namespace tongue::viewer {

struct LiveUpdate {
  // A model different from the last one (the first, or a restarted server's), with its version.
  std::shared_ptr<const std::string> model_json;
  int model_version = 0;
  // The newest state and its number in the stream of states received (1, 2, ...).
  std::shared_ptr<const Frame> frame;
  std::int64_t frame_number = 0;
  // What the feed is doing, when that changed ("waiting for a model ...").
  std::optional<std::string> status;
};

class LiveFeed {
 public:
  using Sink = std::function<void(LiveUpdate)>;
  // Opens the bus (throws std::runtime_error naming the URL when it cannot) and starts the thread.
  LiveFeed(const std::string& url, const std::string& prefix, Sink sink);
  ~LiveFeed();
  LiveFeed(const LiveFeed&) = delete;
  LiveFeed& operator=(const LiveFeed&) = delete;

 private:
  struct State;
  void run();
  std::unique_ptr<State> state_;
  Sink sink_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Simulated time over wall time across the states of the last second or so; restarts when the
// simulated time goes back (a reset).
class RealTimeFactor {
 public:
  std::optional<double> add(double simulated_s, double wall_s);

 private:
  struct Sample {
    double simulated, wall;
  };
  std::optional<Sample> start_, last_;
};

}  // namespace tongue::viewer
