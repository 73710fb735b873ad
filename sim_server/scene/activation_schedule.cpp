#include "scene/activation_schedule.hpp"

#include <algorithm>
#include <string>

#include "common/number_text.hpp"
#include "scene/scene_reader.hpp"

namespace tongue::scene {

namespace {

std::string names_of(const std::vector<model::Muscle>& muscles) {
  std::string s;
  for (const auto& m : muscles) s += (s.empty() ? "" : ", ") + m.name;
  return s;
}

int index_of(const std::vector<model::Muscle>& muscles, const std::string& name) {
  for (std::size_t m = 0; m < muscles.size(); ++m)
    if (muscles[m].name == name) return static_cast<int>(m);
  return -1;
}

// A group is every muscle named as the group or "<group>_<anything>" (GGp: GGp_left,
// GGp_right), so that paired halves and unpaired muscles are addressed alike.
std::vector<int> group_members(const std::vector<model::Muscle>& muscles,
                               const std::string& group) {
  std::vector<int> out;
  const std::string prefix = group + "_";
  for (std::size_t m = 0; m < muscles.size(); ++m) {
    const std::string& name = muscles[m].name;
    if (name == group || name.compare(0, prefix.size(), prefix) == 0)
      out.push_back(static_cast<int>(m));
  }
  return out;
}

}  // namespace

ActivationSchedule::ActivationSchedule(const Scene& scene,
                                       const std::vector<model::Muscle>& muscles)
    : num_muscles_(static_cast<int>(muscles.size())) {
  for (std::size_t i = 0; i < scene.activations.size(); ++i) {
    const ActivationSpec& spec = scene.activations[i];
    const std::string path = "activations[" + std::to_string(i) + "]";
    const auto fail = [&](const std::string& key, const std::string& reason) {
      throw SceneError(scene.source, key.empty() ? path : path + "." + key, reason, spec.line);
    };
    ActivationStep step;
    if (const auto declared = scene.muscle_groups.find(spec.group);
        !spec.group.empty() && declared != scene.muscle_groups.end()) {
      for (const std::string& name : declared->second) {
        const int m = index_of(muscles, name);
        if (m < 0)
          fail("group", "group '" + spec.group + "' names unknown muscle '" + name +
                            "' (known: " + names_of(muscles) + ")");
        step.muscles.push_back(m);
      }
    } else if (!spec.group.empty()) {
      step.muscles = group_members(muscles, spec.group);
      if (step.muscles.empty())
        fail("group", "no muscle is named '" + spec.group + "' or starts with '" + spec.group +
                          "_' (muscles: " + names_of(muscles) + ")");
    } else {
      for (std::size_t k = 0; k < spec.muscles.size(); ++k) {
        const int m = index_of(muscles, spec.muscles[k]);
        if (m < 0)
          fail("muscles[" + std::to_string(k) + "]",
               "unknown muscle '" + spec.muscles[k] + "' (known: " + names_of(muscles) + ")");
        step.muscles.push_back(m);
      }
    }
    if (spec.level) {
      step.level = *spec.level;
    } else {
      // Split by max_force: every muscle of the step gets the same level.
      double total = 0.0;
      for (int m : step.muscles) total += muscles[m].max_force;
      const double force = spec.force.value_or(0.0);
      if (!(total > 0.0)) fail("force", "the muscles have no max_force to share the force");
      // Round-off in a force written as the exact sum must not reject it.
      if (force > total * (1.0 + 1e-12))
        fail("force", common::number_text(force) + " N exceeds the muscles' summed max_force, " +
                          common::number_text(total) + " N");
      step.level = std::min(1.0, force / total);
    }
    step.start = spec.start;
    if (spec.end) step.end = *spec.end;
    steps_.push_back(std::move(step));
  }
}

fem::Vector ActivationSchedule::levels_at(double t) const {
  fem::Vector levels = fem::Vector::Zero(num_muscles_);
  for (const ActivationStep& s : steps_) {
    if (t < s.start - kTimeTolerance || t > s.end + kTimeTolerance) continue;
    for (int m : s.muscles) levels[m] = s.level;
  }
  return levels;
}

}  // namespace tongue::scene
