#include "sequence_player/activation_sequence.hpp"

#include <algorithm>
#include <cmath>

#include "controller/input_error.hpp"
#include "controller/muscle_selection.hpp"
#include "controller/number_text.hpp"
#include "controller/yaml_file.hpp"

namespace tongue::sequence_player {
namespace {

SequenceEntry read_entry(const controller::YamlFile& f, const YAML::Node& n,
                         const std::string& path) {
  f.expect_map(n, path);
  f.check_keys(n, path,
               {"muscle", "start", "end", "level", "force", "level_from", "level_to", "force_from",
                "force_to"});
  SequenceEntry e;
  e.key_path = path;
  e.line = n.Mark().line + 1;
  e.muscle = f.text(f.required(n, path, "muscle"), controller::child_path(path, "muscle"));
  if (const auto v = n["start"]; controller::present(v))
    e.start_s = f.non_negative(v, controller::child_path(path, "start"), "s");
  const bool has_end = controller::present(n["end"]);
  if (has_end) {
    e.end_s = f.number(n["end"], controller::child_path(path, "end"));
    if (!(e.end_s > e.start_s))
      f.fail(controller::child_path(path, "end"),
             "must be after start (" + controller::number_text(e.start_s) + " s), got " +
                 controller::number_text(e.end_s) + " s",
             n["end"]);
  }

  // Exactly one way of giving the value.
  const bool level = controller::present(n["level"]), force = controller::present(n["force"]);
  const bool level_ramp =
      controller::present(n["level_from"]) || controller::present(n["level_to"]);
  const bool force_ramp =
      controller::present(n["force_from"]) || controller::present(n["force_to"]);
  if (level + force + level_ramp + force_ramp != 1)
    f.fail(path,
           "give exactly one of level, force (a step), level_from + level_to, force_from + "
           "force_to (a ramp)",
           n);
  e.unit = level || level_ramp ? SequenceEntry::Unit::level : SequenceEntry::Unit::force;
  const auto value = [&](const char* key) {
    const std::string p = controller::child_path(path, key);
    const YAML::Node v = f.required(n, path, key);
    if (e.unit == SequenceEntry::Unit::level) {
      const double x = f.number(v, p);
      if (x < 0.0 || x > 1.0)
        f.fail(p, "a level must be in [0, 1] of F_max, got " + controller::number_text(x), v);
      return x;
    }
    return f.non_negative(v, p, "N");
  };
  if (level || force) {
    e.from = e.to = value(level ? "level" : "force");
  } else {
    e.ramp = true;
    const std::string stem = level_ramp ? "level" : "force";
    e.from = value((stem + "_from").c_str());
    e.to = value((stem + "_to").c_str());
    if (!has_end) f.fail(controller::child_path(path, "end"), "a ramp needs an end time", n);
  }
  return e;
}

SequenceSpec sequence_from(const controller::YamlFile& f) {
  const YAML::Node& root = f.root();
  f.expect_map(root, "(top level)");
  f.check_keys(root, "", {"duration", "entries"});
  const YAML::Node list = f.required(root, "", "entries");
  f.expect_sequence(list, "entries");
  SequenceSpec spec;
  spec.source = f.source();
  if (const auto d = root["duration"]; controller::present(d)) {
    spec.duration_s = f.number(d, "duration");
    if (!(*spec.duration_s > 0.0))
      f.fail("duration",
             "must be positive, got " + controller::number_text(*spec.duration_s) + " s", d);
  }
  for (std::size_t i = 0; i < list.size(); ++i)
    spec.entries.push_back(read_entry(f, list[i], controller::index_path("entries", i)));
  return spec;
}

}  // namespace

std::int64_t steps_covering(double duration_s, double dt_s) {
  const double ratio = duration_s / dt_s;
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(ratio - 1e-9)));
}

SequenceSpec read_sequence(const std::string& path) {
  return sequence_from(controller::YamlFile::load(path));
}

SequenceSpec parse_sequence(const std::string& text, const std::string& source) {
  return sequence_from(controller::YamlFile::parse(text, source));
}

ActivationSequence::ActivationSequence(const SequenceSpec& spec,
                                       const std::vector<std::string>& muscle_names,
                                       const std::vector<double>& max_forces_n)
    : names_(muscle_names) {
  std::vector<bool> driven(muscle_names.size(), false);
  for (const SequenceEntry& e : spec.entries) {
    Resolved r;
    r.muscles = controller::select_muscles(e.muscle, muscle_names);
    if (r.muscles.empty())
      throw controller::InputError(
          spec.source, controller::child_path(e.key_path, "muscle"),
          "no muscle is named '" + e.muscle + "' or starts with '" + e.muscle +
              "_' (the server's muscles: " + controller::joined_names(muscle_names) + ")",
          e.line);
    r.start_s = e.start_s;
    r.end_s = e.end_s;
    r.ramp = e.ramp;
    r.from_level = e.from;
    r.to_level = e.to;
    if (e.unit == SequenceEntry::Unit::force) {
      // Every muscle of the entry gets the same level: the force over their summed F_max.
      double total = 0.0;
      for (int m : r.muscles) total += max_forces_n[m];
      const double largest = std::max(e.from, e.to);
      // Round-off in a force written as the exact sum must not reject it.
      if (largest > total * (1.0 + 1e-12))
        throw controller::InputError(spec.source, e.key_path,
                                     controller::number_text(largest) +
                                         " N exceeds the summed F_max of " + e.muscle + ", " +
                                         controller::number_text(total) + " N",
                                     e.line);
      r.from_level = std::min(1.0, e.from / total);
      r.to_level = std::min(1.0, e.to / total);
    }
    for (int m : r.muscles) driven[m] = true;
    entries_.push_back(std::move(r));
  }
  for (std::size_t m = 0; m < driven.size(); ++m)
    if (driven[m]) driven_.push_back(static_cast<int>(m));
}

controller::MuscleLevels ActivationSequence::levels_at(double t) const {
  std::vector<double> level(names_.size(), 0.0);
  for (const Resolved& r : entries_) {
    if (t < r.start_s - kTimeTolerance || t > r.end_s + kTimeTolerance) continue;
    double value = r.from_level;
    if (r.ramp) {
      const double s = std::clamp((t - r.start_s) / (r.end_s - r.start_s), 0.0, 1.0);
      value = r.from_level + (r.to_level - r.from_level) * s;
    }
    for (int m : r.muscles) level[m] = value;
  }
  controller::MuscleLevels out;
  for (int m : driven_) {
    out.names.push_back(names_[m]);
    out.levels.push_back(level[m]);
  }
  return out;
}

}  // namespace tongue::sequence_player
