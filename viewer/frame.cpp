#include "viewer/frame.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

namespace tongue::viewer {

Frame frame_from_state(const tongue_lcm::lcmt_tongue_state& s) {
  Frame f;
  f.step = s.step;
  f.time = s.time;
  f.nodes = s.node_indices;
  f.positions = s.positions;
  f.activations = s.activations;
  f.muscle_lengths = s.muscle_lengths;
  f.iterations = s.newton_iterations;
  f.residual = s.residual_norm;
  f.wall_time = s.step_wall_time;
  f.cuts = s.step_cuts;
  f.converged = s.converged;
  f.status = s.status;
  f.contact_nodes = s.contact_nodes;
  f.contact_obstacles = s.contact_obstacles;
  f.contact_forces = s.contact_forces;
  f.obstacle_forces = s.obstacle_forces;
  f.max_penetration = s.max_penetration;
  f.reduced_correction = s.reduced_model_correction;
  return f;
}

double rounded_position(double x) {
  return std::round(x * 1e8) / 1e8;
}

std::string frame_json(const Frame& f, std::int64_t dropped) {
  using nlohmann::json;
  std::vector<double> positions(f.positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i)
    positions[i] = rounded_position(f.positions[i]);
  // A number that is not finite has no JSON form: null, which the page shows as unknown.
  auto number = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  const json j = {
      {"type", "frame"},
      {"run", f.run},
      {"index", f.index ? json(*f.index) : json(nullptr)},
      {"step", f.step},
      {"time", number(f.time)},
      {"nodes", f.nodes ? json(*f.nodes) : json(nullptr)},
      {"positions", positions},
      {"activations", f.activations},
      {"muscle_lengths", f.muscle_lengths},
      {"iterations", f.iterations},
      {"residual", number(f.residual)},
      {"wall_time", number(f.wall_time)},
      {"cuts", f.cuts},
      {"converged", f.converged},
      {"status", f.status},
      {"real_time_factor", f.real_time_factor ? number(*f.real_time_factor) : json(nullptr)},
      {"contacts",
       {{"nodes", f.contact_nodes},
        {"obstacles", f.contact_obstacles},
        {"forces", f.contact_forces}}},
      {"obstacle_forces", f.obstacle_forces},
      {"max_penetration", number(f.max_penetration)},
      {"reduced_correction", number(f.reduced_correction)},
      {"dropped", dropped}};
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace tongue::viewer
