#include "run_figures.hpp"

#include <lcm/eventlog.h>

#include <cmath>
#include <memory>
#include <set>
#include <string>

#include "run_file/run_file_reader.hpp"

namespace tongue::runner {
namespace {

namespace L = run_file::layout;

// The landmark node sets of the built-in tongue, in the order a summary lists them.
constexpr const char* kLandmarks[] = {"tip",          "blade", "palatal_dorsum",
                                      "velar_dorsum", "root",  "gg_insertion"};

}  // namespace

RunFigures read_run_figures(const std::filesystem::path& run_file) {
  const run_file::RunFileReader h5(run_file.string());
  const std::vector<double> time = h5.doubles(L::kTime);
  const std::vector<double> positions = h5.doubles(L::kPositions);
  if (time.empty()) throw run_file::RunFileError(run_file.string(), L::kTime, "no frames");
  const std::size_t frames = time.size();
  const std::size_t values_per_frame = positions.size() / frames;

  RunFigures f;
  f.steps = static_cast<int>(frames) - 1;
  f.simulated = time.back() - time.front();
  for (const double w : h5.doubles(L::kWallTime)) f.physics_wall += w;
  for (const int i : h5.ints(L::kIterations)) f.newton_iterations += i;
  for (const int c : h5.ints(L::kCuts)) f.step_cuts += c;
  if (h5.has_attribute(L::kRoot, L::kStatusAttribute))
    f.status = h5.string_attribute(L::kRoot, L::kStatusAttribute);

  for (const char* name : kLandmarks) {
    const std::string set = L::node_set(name);
    if (!h5.exists(set)) continue;
    const std::vector<int> nodes = h5.ints(set);
    if (nodes.empty()) continue;
    const std::size_t at = 3 * static_cast<std::size_t>(nodes.front());
    LandmarkMotion m;
    m.name = name;
    for (std::size_t k = 0; k < frames; ++k) {
      std::array<double, 3> d{};
      for (int c = 0; c < 3; ++c) {
        d[c] = 1e3 * (positions[k * values_per_frame + at + c] - positions[at + c]);  // mm
      }
      const double distance = std::hypot(d[0], d[1], d[2]);
      if (distance > m.peak_mm) {
        m.peak_mm = distance;
        m.peak_time = time[k];
      }
      m.final_mm = d;
    }
    f.landmarks.push_back(m);
  }
  return f;
}

std::optional<BusFigures> read_bus_figures(const std::filesystem::path& lcm_log,
                                           const std::string& state_channel,
                                           const std::string& activation_channel) {
  const std::unique_ptr<lcm_eventlog_t, decltype(&lcm_eventlog_destroy)> log(
      lcm_eventlog_create(lcm_log.c_str(), "r"), &lcm_eventlog_destroy);
  if (!log) return std::nullopt;
  BusFigures b;
  std::set<std::string> activations;  // their bytes
  std::int64_t first = 0, last = 0;
  while (lcm_eventlog_event_t* event = lcm_eventlog_read_next_event(log.get())) {
    const std::string channel(event->channel, event->channellen);
    if (channel == state_channel) {
      if (b.states++ == 0) first = event->timestamp;
      last = event->timestamp;
    } else if (channel == activation_channel) {
      const auto* data = static_cast<const char*>(event->data);
      if (activations.insert(std::string(data, data + event->datalen)).second) {
        ++b.activations;
      } else {
        ++b.repeated_activations;
      }
    }
    lcm_eventlog_free_event(event);
  }
  b.state_span = 1e-6 * static_cast<double>(last - first);
  return b;
}

}  // namespace tongue::runner
