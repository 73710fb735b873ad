#pragma once
// An activation sequence: steps and ramps of activation per muscle or group over time, as a
// fraction of max force (level) or in newtons (force: split over the named muscles in proportion
// to their F_max, every one getting the same level, as a scene's activations are).
//
// File (YAML; times in s, forces in N, levels in [0, 1] of F_max):
//   duration: 0.12          # optional: the player ends after the step reaching this time
//   entries:
//     - {muscle: SG, start: 0.0, end: 0.12, force: 3.0}          # step of 3 N over SG_left/right
//     - {muscle: GGp_left, start: 0.1, level: 0.2}               # step to the end of the run
//     - {muscle: GGp, start: 0.1, end: 0.2, level_from: 0.0, level_to: 0.5}   # ramp
//     - {muscle: HG, start: 0.0, end: 0.05, force_from: 0, force_to: 6.5}      # ramp in N
// muscle: a muscle or a group (SG: SG, SG_left, SG_right). An entry is active while
// start <= t <= end (start default 0; end optional for a step, required for a ramp, > start);
// a ramp goes linearly from its first value at start to its second at end. Where active entries
// overlap on a muscle, the later one in the file sets its level; a muscle some entry names is at
// level 0 while none of its entries is active. Muscles no entry names are never sent, so they keep
// whatever level the server has (another controller may drive them).
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "controller/controller_bus.hpp"

namespace tongue::sequence_player {

struct SequenceEntry {
  enum class Unit { level, force };
  std::string muscle;  // a muscle or a group
  double start_s = 0.0;
  double end_s = std::numeric_limits<double>::infinity();
  Unit unit = Unit::level;
  double from = 0.0;  // at start (level or N)
  double to = 0.0;    // at end; equal to from for a step
  bool ramp = false;
  std::string key_path;  // "entries[2]", for errors
  int line = 0;
};

struct SequenceSpec {
  std::string source;
  std::optional<double> duration_s;  // none: no end of its own (--max-steps ends the run)
  std::vector<SequenceEntry> entries;
};

// The number of steps of dt that cover duration (the last one may end past it), as sim_batch
// counts a scene's steps: ceil(duration / dt) with round-off forgiven.
std::int64_t steps_covering(double duration_s, double dt_s);

// Throws InputError naming the file, key and line: unknown or missing keys, not exactly one of
// level / force / level_from+level_to / force_from+force_to, a level outside [0, 1], a negative
// force or time, end <= start, a ramp without end, a duration <= 0.
SequenceSpec read_sequence(const std::string& path);
SequenceSpec parse_sequence(const std::string& text, const std::string& source);

class ActivationSequence {
 public:
  // Times closer than this count as equal [s], as in the scene's schedule: (k + 1) dt and a
  // written end time differ by round-off.
  static constexpr double kTimeTolerance = 1e-9;

  // Resolves the entries against the model's muscles. Throws InputError naming the entry for a
  // name that selects no muscle and for a force beyond the selected muscles' summed F_max.
  ActivationSequence(const SequenceSpec& spec, const std::vector<std::string>& muscle_names,
                     const std::vector<double>& max_forces_n);

  // Levels at time t [s] of every muscle some entry names (model order).
  controller::MuscleLevels levels_at(double t) const;
  const std::vector<int>& driven_muscles() const { return driven_; }

 private:
  struct Resolved {
    std::vector<int> muscles;
    double start_s, end_s;
    double from_level, to_level;  // levels (forces already divided by the summed F_max)
    bool ramp;
  };
  std::vector<std::string> names_;
  std::vector<Resolved> entries_;
  std::vector<int> driven_;
};

}  // namespace tongue::sequence_player
