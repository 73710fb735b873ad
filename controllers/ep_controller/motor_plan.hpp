#pragma once
// A motor plan for the equilibrium-point controller: per muscle or group, the shifts of its
// threshold length, Delta-lambda (mm), reached one after the other. Each target is approached
// linearly over `transition` and then held for `hold` (Payan & Perrier 1997: linear shifts of
// lambda between targets), so target i (0-based) is reached at start + i (transition + hold) +
// transition. Before start Delta-lambda is 0 (lambda = rest length); after the last target it
// stays there. Muscles not in the plan keep Delta-lambda 0.
//
// File (YAML; durations in s, shifts in mm, rho in N):
//   transition: 0.05        # optional, default for every entry (default 0.05 s)
//   hold: 0.1               # optional, default 0.1 s
//   start: 0.0              # optional, when the first transition begins (default 0 s)
//   delta_lambda_mm:        # required: muscle or group -> targets
//     GGa: [-10, 20]
//     SG: {targets: [0, -15], transition: 0.08, hold: 0.1, start: 0.02}
//   rho: {flexor: 0.005}    # optional: rho [N] per muscle or group, over the default table
#include <string>
#include <utility>
#include <vector>

namespace tongue::ep_controller {

// One muscle's (or group's) Delta-lambda over time.
struct DeltaLambdaTrack {
  std::vector<double> targets_mm;
  double transition_s = 0.05;
  double hold_s = 0.1;
  double start_s = 0.0;

  // Delta-lambda at time t [s], in mm.
  double at(double t) const;
};

struct PlanEntry {
  std::string name;  // a muscle or a group
  DeltaLambdaTrack track;
  std::string key_path;  // e.g. "delta_lambda_mm.GGa", for errors
  int line = 0;
};

struct RhoEntry {
  std::string name;
  double rho_n = 0.0;
  std::string key_path;
  int line = 0;
};

struct MotorPlanSpec {
  std::string source;  // the file, for errors
  std::vector<PlanEntry> entries;
  std::vector<RhoEntry> rho;
};

// Throws InputError naming the file, key and line for an unknown or repeated key, a missing
// delta_lambda_mm, an empty target list, a non-number, a negative duration, rho <= 0.
MotorPlanSpec read_motor_plan(const std::string& path);
MotorPlanSpec parse_motor_plan(const std::string& text, const std::string& source);

// A plan resolved against a model's muscles.
class MotorPlan {
 public:
  // Throws InputError (naming the entry) for a name that selects no muscle, and for a muscle
  // selected by two entries (e.g. SG and SG_left): which one should win is not obvious.
  MotorPlan(const MotorPlanSpec& spec, const std::vector<std::string>& muscle_names);

  // Delta-lambda [mm] of muscle m (model order) at time t [s].
  double delta_lambda_mm(int muscle, double t) const;
  int num_muscles() const { return static_cast<int>(track_of_.size()); }

 private:
  std::vector<DeltaLambdaTrack> tracks_;
  std::vector<int> track_of_;  // per muscle, index into tracks_ or -1
};

}  // namespace tongue::ep_controller
