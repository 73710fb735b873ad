#include "logging/scene_run_file.hpp"

#include <vector>

namespace tongue::logging {

std::unique_ptr<PositionLog> open_scene_run_file(const std::string& path, const scene::Scene& scene,
                                                 const scene::BuiltScene& built) {
  const bool dynamic = scene.analysis.type == scene::AnalysisType::dynamic;
  PositionLogOptions options;
  // A static run's frames are load factors, not times. (assign, not = "1": GCC 12 warns
  // falsely about overlapping memcpy for a one-character literal.)
  if (!dynamic) options.time_unit.assign(1, '1');
  std::vector<MuscleDescription> muscles;
  if (built.muscles)
    for (const auto& m : built.muscles->muscles()) muscles.push_back({m.name, m.max_force});
  auto log = std::make_unique<PositionLog>(path, built.solid->mesh(), scene.text, options, muscles);
  log->set_attribute("analysis", dynamic ? "dynamic" : "static");
  // What frame 0 shows, so that pictures can compare the end with rest under gravity.
  log->set_attribute("initial_state",
                     dynamic && scene.analysis.settle
                         ? "settled: static equilibrium under the loads, muscles off"
                         : "reference: the rest positions");
  log->set_attribute("status", "running");
  return log;
}

MuscleFrame scene_muscle_frame(const scene::BuiltScene& built, const fem::Vector& u,
                               const fem::Vector* v) {
  MuscleFrame frame;
  if (!built.muscles) return frame;
  const model::MuscleForces& m = *built.muscles;
  frame.activations = m.activations();
  frame.lengths = m.muscle_lengths(u);
  frame.velocities = v ? m.muscle_velocities(u, *v) : fem::Vector::Zero(m.num_muscles()).eval();
  return frame;
}

}  // namespace tongue::logging
