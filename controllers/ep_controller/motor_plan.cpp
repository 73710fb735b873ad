#include "ep_controller/motor_plan.hpp"

#include <cmath>

#include "controller/input_error.hpp"
#include "controller/muscle_selection.hpp"
#include "controller/number_text.hpp"
#include "controller/yaml_file.hpp"

namespace tongue::ep_controller {

double DeltaLambdaTrack::at(double t) const {
  if (targets_mm.empty() || t <= start_s) return 0.0;
  const double elapsed = t - start_s;
  const double period = transition_s + hold_s;
  const std::size_t n = targets_mm.size();
  if (!(period > 0.0)) return targets_mm.back();  // one target, reached at once
  const double segments = std::floor(elapsed / period);
  if (segments >= static_cast<double>(n)) return targets_mm.back();
  const auto i = static_cast<std::size_t>(segments);
  const double from = i == 0 ? 0.0 : targets_mm[i - 1];
  const double into = elapsed - segments * period;
  if (into < transition_s) return from + (targets_mm[i] - from) * (into / transition_s);
  return targets_mm[i];
}

namespace {

struct Durations {
  double transition_s = 0.05;
  double hold_s = 0.1;
  double start_s = 0.0;
};

// Reads transition, hold and start where present in n (the top level or an entry).
void read_durations(const controller::YamlFile& f, const YAML::Node& n, const std::string& path,
                    Durations& d) {
  if (const auto v = n["transition"]; controller::present(v))
    d.transition_s = f.non_negative(v, controller::child_path(path, "transition"), "s");
  if (const auto v = n["hold"]; controller::present(v))
    d.hold_s = f.non_negative(v, controller::child_path(path, "hold"), "s");
  if (const auto v = n["start"]; controller::present(v))
    d.start_s = f.non_negative(v, controller::child_path(path, "start"), "s");
}

PlanEntry read_entry(const controller::YamlFile& f, const std::string& name, const YAML::Node& n,
                     const std::string& path, const Durations& defaults) {
  PlanEntry e;
  e.name = name;
  e.key_path = path;
  e.line = n.Mark().line + 1;
  Durations d = defaults;
  if (n.IsSequence()) {
    e.track.targets_mm = f.numbers(n, path);
  } else if (n.IsMap()) {
    f.check_keys(n, path, {"targets", "transition", "hold", "start"});
    e.track.targets_mm =
        f.numbers(f.required(n, path, "targets"), controller::child_path(path, "targets"));
    read_durations(f, n, path, d);
  } else {
    f.fail(path,
           "expected a list of Delta-lambda targets in mm, or {targets: [...], transition, hold, "
           "start}",
           n);
  }
  e.track.transition_s = d.transition_s;
  e.track.hold_s = d.hold_s;
  e.track.start_s = d.start_s;
  if (e.track.targets_mm.size() > 1 && !(d.transition_s + d.hold_s > 0.0))
    f.fail(path,
           "transition and hold are both 0 s: only the last of several targets would ever be used",
           n);
  return e;
}

MotorPlanSpec plan_from(const controller::YamlFile& f) {
  const YAML::Node& root = f.root();
  f.expect_map(root, "(top level)");
  f.check_keys(root, "", {"transition", "hold", "start", "delta_lambda_mm", "rho"});
  Durations defaults;
  read_durations(f, root, "", defaults);
  MotorPlanSpec spec;
  spec.source = f.source();
  const YAML::Node plan = f.required(root, "", "delta_lambda_mm");
  f.expect_map(plan, "delta_lambda_mm");
  f.check_unique_keys(plan, "delta_lambda_mm");
  for (auto it = plan.begin(); it != plan.end(); ++it) {
    const std::string name = it->first.Scalar();
    spec.entries.push_back(
        read_entry(f, name, it->second, controller::child_path("delta_lambda_mm", name), defaults));
  }
  if (const auto rho = root["rho"]; controller::present(rho)) {
    f.expect_map(rho, "rho");
    f.check_unique_keys(rho, "rho");
    for (auto it = rho.begin(); it != rho.end(); ++it) {
      const std::string name = it->first.Scalar();
      const std::string path = controller::child_path("rho", name);
      RhoEntry r{name, f.number(it->second, path), path, it->second.Mark().line + 1};
      if (!(r.rho_n > 0.0))
        f.fail(path, "rho must be positive, got " + controller::number_text(r.rho_n) + " N",
               it->second);
      spec.rho.push_back(r);
    }
  }
  return spec;
}

}  // namespace

MotorPlanSpec read_motor_plan(const std::string& path) {
  return plan_from(controller::YamlFile::load(path));
}

MotorPlanSpec parse_motor_plan(const std::string& text, const std::string& source) {
  return plan_from(controller::YamlFile::parse(text, source));
}

MotorPlan::MotorPlan(const MotorPlanSpec& spec, const std::vector<std::string>& muscle_names)
    : track_of_(muscle_names.size(), -1) {
  std::vector<std::string> set_by(muscle_names.size());
  for (const PlanEntry& e : spec.entries) {
    const std::vector<int> members = controller::select_muscles(e.name, muscle_names);
    if (members.empty())
      throw controller::InputError(
          spec.source, e.key_path,
          "no muscle is named '" + e.name + "' or starts with '" + e.name +
              "_' (the server's muscles: " + controller::joined_names(muscle_names) + ")",
          e.line);
    for (int m : members) {
      if (track_of_[m] >= 0)
        throw controller::InputError(spec.source, e.key_path,
                                     "muscle " + muscle_names[m] + " is also set by " + set_by[m],
                                     e.line);
      track_of_[m] = static_cast<int>(tracks_.size());
      set_by[m] = e.key_path;
    }
    tracks_.push_back(e.track);
  }
}

double MotorPlan::delta_lambda_mm(int muscle, double t) const {
  const int track = track_of_.at(static_cast<std::size_t>(muscle));
  return track < 0 ? 0.0 : tracks_[static_cast<std::size_t>(track)].at(t);
}

}  // namespace tongue::ep_controller
