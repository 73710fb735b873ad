#pragma once
// What a controller program plugs into the control loop (control_loop.hpp): it learns the model,
// sees every state in order, and says which levels to use during a step. It knows nothing of LCM,
// so it can be tested without a bus.
#include <cstdint>
#include <optional>
#include <string>

#include "controller/controller_bus.hpp"

namespace tongue::controller {

class Controller {
 public:
  virtual ~Controller() = default;

  // The first model: resolve muscle names, read dt. Throws InputError when the controller's
  // input does not fit this model (an unknown muscle, a force beyond a muscle's max).
  virtual void start(const Model& model) = 0;
  // Every state received, in order (after start). A step lower than the previous one means the
  // server was reset.
  virtual void observe(const State& state) = 0;
  // The levels for the muscles this controller drives, to be used during step `step` (from
  // time (step - 1) dt to step dt), given the states observed so far.
  virtual MuscleLevels command(std::int64_t step) = 0;
  // The last step the controller has levels for (e.g. the end of a replayed log); the loop ends
  // after that step's state. nullopt: no end of its own.
  virtual std::optional<std::int64_t> last_step() const { return std::nullopt; }
  // A few words on what the controller did, for the summary line (may be empty).
  virtual std::string summary() const { return {}; }
};

}  // namespace tongue::controller
