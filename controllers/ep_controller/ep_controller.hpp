#pragma once
// The equilibrium-point controller: every muscle of the model driven by the lambda model
// (lambda_model.hpp) in closed loop on the lengths and velocities the server publishes, its
// threshold lambda = rest length + Delta-lambda of the motor plan (motor_plan.hpp).
//
// - Rest length: the muscle's length in the first state seen (the state of step 0 when the
//   controller is there from the start: after settling, the tongue at rest under gravity). With
//   Delta-lambda 0 a muscle at rest has A = 0 and no force; it pulls only once stretched beyond
//   its rest length (the stretch reflex), so the tongue at rest stays at rest.
// - Delay: D = max(1, delay / dt) steps; the command for step k + 1 uses the feedback of step
//   k + 1 - D (at least one step: the state of step k + 1 is what the command produces),
//   interpolated between the states around it when D is not whole (delay_buffer.hpp).
// - Time: lambda is taken at the end of the step it is for, t = (k + 1) dt, as a scene's
//   activation schedule is.
// - Force development: the levels sent follow the law's through a first-order lag
//   (force_lag.hpp, tau 100 ms by default; 0 gives the bare law).
// - Every muscle is sent every step (those outside the plan hold lambda at rest length).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "controller/controller.hpp"
#include "ep_controller/delay_buffer.hpp"
#include "ep_controller/force_lag.hpp"
#include "ep_controller/lambda_model.hpp"
#include "ep_controller/motor_plan.hpp"

namespace tongue::ep_controller {

struct EpSettings {
  double delay_s = 0.012;  // reflex delay d [s] (docs/controllers.md)
  bool velocity_factor = true;
  double force_lag_s = 0.1;  // time constant of force development [s]; 0: none
  LambdaConstants constants;
};

class EpController final : public controller::Controller {
 public:
  EpController(MotorPlanSpec plan, EpSettings settings);

  // Throws InputError (naming the plan file) for plan names that select no muscle, and for a
  // muscle without rho; std::runtime_error for a model without a usable dt.
  void start(const controller::Model& model) override;
  // Throws std::runtime_error when a length or velocity is not finite or a length is not > 0.
  void observe(const controller::State& state) override;
  controller::MuscleLevels command(std::int64_t step) override;
  std::string summary() const override;

  double delay_steps() const { return history_ ? history_->delay_steps() : 0.0; }
  // The law's figures for each muscle in the last command (model order), before the force lag.
  const std::vector<MuscleCommand>& last_commands() const { return last_; }
  const std::vector<MuscleLaw>& laws() const { return laws_; }

 private:
  MotorPlanSpec spec_;
  EpSettings settings_;
  std::optional<MotorPlan> plan_;
  std::vector<std::string> names_;
  std::vector<MuscleLaw> laws_;
  double dt_ = 0.0;  // s
  bool have_rest_lengths_ = false;
  std::optional<DelayBuffer> history_;
  std::optional<ForceLag> lag_;
  std::vector<MuscleCommand> last_;
  double peak_level_ = 0.0;
  std::string peak_muscle_;
  std::int64_t peak_step_ = 0;
};

}  // namespace tongue::ep_controller
