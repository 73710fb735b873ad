#include "viewer/run_replay.hpp"

#include <filesystem>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "run_file/run_file_reader.hpp"

namespace tongue::viewer {
namespace {

namespace L = run_file::layout;

// A time series of rows values per frame, or empty when the file lacks it.
std::vector<double> series(const run_file::RunFileReader& file, const char* name,
                           std::size_t frames, std::size_t per_frame) {
  if (!file.exists(name)) return {};
  std::vector<double> values = file.doubles(name);
  if (values.size() != frames * per_frame)
    throw std::invalid_argument(
        file.path() + ": " + name + " holds " + std::to_string(values.size()) + " values, not " +
        std::to_string(per_frame) + " for each of " + std::to_string(frames) + " frames");
  return values;
}

// The same, for a series the page cannot draw without: its absence is an error naming the file
// and the dataset.
std::vector<double> required_series(const run_file::RunFileReader& file, const char* name,
                                    std::size_t frames, std::size_t per_frame) {
  std::vector<double> values = series(file, name, frames, per_frame);
  if (values.empty() && frames * per_frame > 0)
    throw std::invalid_argument(file.path() + ": " + name + ": missing");
  return values;
}

std::vector<int> int_series(const run_file::RunFileReader& file, const char* name,
                            std::size_t frames) {
  std::vector<int> values = file.ints(name);
  if (values.size() != frames)
    throw std::invalid_argument(file.path() + ": " + name + " has not one value per frame");
  return values;
}

}  // namespace

RunReplay::RunReplay(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) runs_.push_back(load(path));
}

RunReplay::Run RunReplay::load(const std::string& path) {
  const run_file::RunFileReader file(path);
  Run r;
  r.path = path;
  const DrawingModel model = drawing_model(file);
  r.model_json = viewer::model_json(model, 0);
  r.nodes = static_cast<std::size_t>(model.num_nodes());
  r.muscles = model.muscles.size();
  r.obstacles = model.obstacles.size();
  r.time = file.doubles(L::kTime);
  const std::size_t frames = r.time.size();
  if (frames == 0) throw std::invalid_argument(path + ": the run has no frame");
  r.positions = required_series(file, L::kPositions, frames, 3 * r.nodes);
  r.activations = required_series(file, L::kActivations, frames, r.muscles);
  r.lengths = required_series(file, L::kMuscleLength, frames, r.muscles);
  r.residual = series(file, L::kResidual, frames, 1);
  r.wall_time = series(file, L::kWallTime, frames, 1);
  r.correction = series(file, L::kReducedCorrection, frames, 1);
  r.iterations = int_series(file, L::kIterations, frames);
  r.cuts = int_series(file, L::kCuts, frames);
  if (r.obstacles > 0) {
    r.node_forces = required_series(file, L::kContactNodeForce, frames, 3 * r.nodes);
    r.obstacle_forces = required_series(file, L::kContactObstacleForce, frames, 3 * r.obstacles);
    r.penetration = required_series(file, L::kContactMaxPenetration, frames, 1);
  }
  r.status = file.has_attribute(L::kRoot, L::kStatusAttribute)
                 ? file.string_attribute(L::kRoot, L::kStatusAttribute)
                 : "";
  r.analysis =
      file.has_attribute(L::kRoot, "analysis") ? file.string_attribute(L::kRoot, "analysis") : "";
  return r;
}

std::string RunReplay::session_json() const {
  using nlohmann::json;
  json runs = json::array();
  for (const Run& r : runs_) {
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(r.path, ec);
    runs.push_back({{"name", std::filesystem::path(r.path).filename().string()},
                    {"path", ec ? r.path : absolute.string()},
                    {"frames", r.time.size()},
                    {"times", r.time},
                    {"status", r.status},
                    {"analysis", r.analysis}});
  }
  return json{{"mode", "replay"}, {"runs", runs}}.dump(-1, ' ', false,
                                                       json::error_handler_t::replace);
}

Frame RunReplay::frame(int run, std::int64_t index) const {
  const Run& r = runs_.at(run);
  const auto i = static_cast<std::size_t>(index);
  auto row = [i](const std::vector<double>& v, std::size_t width) {
    return std::vector<double>(v.begin() + i * width, v.begin() + (i + 1) * width);
  };
  Frame f;
  f.run = run;
  f.index = index;
  f.step = index;
  f.time = r.time[i];
  f.positions = row(r.positions, 3 * r.nodes);
  if (!r.activations.empty()) f.activations = row(r.activations, r.muscles);
  if (!r.lengths.empty()) f.muscle_lengths = row(r.lengths, r.muscles);
  f.iterations = r.iterations[i];
  if (!r.residual.empty()) f.residual = r.residual[i];
  if (!r.wall_time.empty()) f.wall_time = r.wall_time[i];
  f.cuts = r.cuts[i];
  if (!r.correction.empty()) f.reduced_correction = r.correction[i];
  // Simulated time since the previous frame over the wall time it took.
  if (i > 0 && f.wall_time > 0.0) f.real_time_factor = (r.time[i] - r.time[i - 1]) / f.wall_time;
  if (r.obstacles > 0) {
    for (std::size_t n = 0; n < r.nodes; ++n) {
      const double* force = &r.node_forces[(i * r.nodes + n) * 3];
      if (force[0] == 0.0 && force[1] == 0.0 && force[2] == 0.0) continue;
      f.contact_nodes.push_back(static_cast<int>(n));
      f.contact_obstacles.push_back(-1);
      f.contact_forces.insert(f.contact_forces.end(), force, force + 3);
    }
    f.obstacle_forces = row(r.obstacle_forces, 3 * r.obstacles);
    f.max_penetration = r.penetration[i];
  }
  return f;
}

}  // namespace tongue::viewer
