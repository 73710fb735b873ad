#include "viewer/live_feed.hpp"

#include <chrono>
#include <cstdio>
#include <deque>

#include "common/rate_limited_reporter.hpp"
#include "controller/controller_bus.hpp"

namespace tongue::viewer {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kDescribeEvery = std::chrono::seconds(1);  // while no model is known
constexpr auto kQuietAfter = std::chrono::seconds(3);     // no state: say so on the page
constexpr int kPollMs = 50;
constexpr double kWindowS = 1.0;  // the real-time factor's span of states

double seconds(Clock::time_point t) {
  return std::chrono::duration<double>(t.time_since_epoch()).count();
}

}  // namespace

std::optional<double> RealTimeFactor::add(double simulated_s, double wall_s) {
  if (!start_ || !last_ || simulated_s < last_->simulated) start_ = Sample{simulated_s, wall_s};
  last_ = Sample{simulated_s, wall_s};
  const double wall = last_->wall - start_->wall;
  const std::optional<double> factor =
      wall > 0.0 ? std::optional<double>((last_->simulated - start_->simulated) / wall)
                 : std::nullopt;
  // A new window once this one spans a second: the factor follows changes of pace.
  if (wall >= kWindowS) start_ = last_;
  return factor;
}

struct LiveFeed::State {
  std::string url, prefix;
  std::unique_ptr<controller::ControllerBus> bus;
  common::RateLimitedReporter reports;  // a model refused: at most a line a second
};

LiveFeed::LiveFeed(const std::string& url, const std::string& prefix, Sink sink)
    : state_(std::make_unique<State>()), sink_(std::move(sink)) {
  state_->url = url;
  state_->prefix = prefix;
  state_->bus = std::make_unique<controller::ControllerBus>(url, bus::Channels(prefix),
                                                            "tongue_viewer", "tongue_viewer");
  thread_ = std::thread([this] { run(); });
}

LiveFeed::~LiveFeed() {
  stop_ = true;
  thread_.join();
}

void LiveFeed::run() {
  const bus::Channels channels(state_->prefix);
  std::string model_text;  // the current model's JSON without its version, to tell changes
  int version = 0;
  bool have_model = false;
  std::int64_t received = 0;
  Clock::time_point last_describe{}, last_state = Clock::now();
  std::int64_t rejected_at_last_state = 0;
  bool quiet_reported = false;
  RealTimeFactor pace;
  auto status = [this](std::string text) {
    LiveUpdate u;
    u.status = std::move(text);
    sink_(std::move(u));
  };
  try {
    while (!stop_) {
      controller::ControllerBus& bus = *state_->bus;
      bus.poll(kPollMs);
      const Clock::time_point now = Clock::now();
      if (!have_model && now - last_describe >= kDescribeEvery) {
        if (last_describe == Clock::time_point{})
          status("waiting for a model on " + channels.model + " at " + state_->url +
                 " (asking with describe every second)");
        bus.send_command(bus::Command::describe);
        last_describe = now;
      }
      if (!bus.models().empty()) {
        const controller::Model message = std::move(bus.models().back());
        bus.models().clear();
        try {
          const DrawingModel drawing = drawing_model(message);
          const std::string text = model_json(drawing, 0);
          if (!have_model || text != model_text) {
            model_text = text;
            bus.set_model(message);
            have_model = true;
            LiveUpdate u;
            u.model_version = ++version;
            u.model_json = std::make_shared<const std::string>(model_json(drawing, version));
            sink_(std::move(u));
            status("model " + std::to_string(version) +
                   " received: " + std::to_string(message.num_nodes) + " nodes, " +
                   std::to_string(message.num_muscles) + " muscles");
          }
        } catch (const std::invalid_argument& e) {
          state_->reports.report(
              "model", "tongue_viewer: ignored a model on " + channels.model + ": " + e.what());
        }
      }
      if (have_model && !bus.states().empty()) {
        received += static_cast<std::int64_t>(bus.states().size());
        const controller::State state = std::move(bus.states().back());
        bus.states().clear();
        auto frame = std::make_shared<Frame>(frame_from_state(state));
        frame->real_time_factor = pace.add(state.time, seconds(now));
        LiveUpdate u;
        u.frame = std::move(frame);
        u.frame_number = received;
        sink_(std::move(u));
        last_state = now;
        rejected_at_last_state = bus.rejected();
        if (quiet_reported) status("receiving states on " + channels.state);
        quiet_reported = false;
      }
      if (have_model && !quiet_reported && now - last_state >= kQuietAfter) {
        status("no state on " + channels.state + " for 3 s");
        quiet_reported = true;
      }
      // States rejected while none fit: the server was probably restarted with another scene
      // (its muscles differ). Forget the model and ask again.
      if (have_model && now - last_state >= kQuietAfter &&
          bus.rejected() > rejected_at_last_state) {
        state_->bus = std::make_unique<controller::ControllerBus>(state_->url, channels,
                                                                  "tongue_viewer", "tongue_viewer");
        have_model = false;
        last_describe = Clock::time_point{};
        last_state = now;
        rejected_at_last_state = 0;
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tongue_viewer: the bus failed: %s\n", e.what());
    status(std::string("the bus failed: ") + e.what());
  }
}

}  // namespace tongue::viewer
