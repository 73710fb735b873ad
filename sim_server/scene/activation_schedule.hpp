#pragma once
// A scene's activation steps (scene.hpp, `activations`) resolved against the built muscles: each
// step as muscle indices and one level, and the levels of all muscles at any time.
#include <limits>
#include <vector>

#include "fem/types.hpp"
#include "model/muscle.hpp"
#include "scene/scene.hpp"

namespace tongue::scene {

struct ActivationStep {
  std::vector<int> muscles;  // indices into the muscle list, in the order named
  double level = 0.0;        // [1] of each muscle's max_force
  double start = 0.0;        // s
  double end = std::numeric_limits<double>::infinity();  // s
};

class ActivationSchedule {
 public:
  // Times closer than this count as equal [s]: t_{n+1} accumulates round-off from summing dt.
  static constexpr double kTimeTolerance = 1e-9;

  ActivationSchedule() = default;  // no muscles, no steps

  // Resolves the scene's activations against muscles; a group is the scene's declared group of
  // that name (Scene::muscle_groups), else every muscle named G or G_<anything>. Throws SceneError
  // (scene_reader.hpp) with the key path of the entry for an unknown muscle name, a group that
  // matches no muscle, and a force beyond the named muscles' summed max_force.
  ActivationSchedule(const Scene& scene, const std::vector<model::Muscle>& muscles);

  int num_muscles() const { return num_muscles_; }
  const std::vector<ActivationStep>& steps() const { return steps_; }

  // Levels of all muscles at time t [s]: a step is active while start <= t <= end (within
  // kTimeTolerance); a later active step overrides an earlier one on the muscles they share;
  // muscles without an active step are at 0.
  fem::Vector levels_at(double t) const;

 private:
  int num_muscles_ = 0;
  std::vector<ActivationStep> steps_;
};

}  // namespace tongue::scene
