#pragma once
// The messages the server publishes, built from its run: the model (at start and on "describe")
// and the state of the last accepted step.
#include <cstdint>
#include <string>
#include <vector>

#include "bus/messages.hpp"
#include "scene_run/scene_run.hpp"

namespace tongue::server {

// The model of run's scene: mesh, rest positions, muscles, landmarks, dt and the scene's text.
tongue_lcm::lcmt_tongue_model model_message(const scene_run::SceneRun& run, std::int64_t utime);

// What a state says beyond the run's state: how the server stands.
struct StateNotes {
  std::string status = "ok";  // "ok", "paused", or why the run stopped
  bool converged = true;      // false: the last step failed, the state is the one before it
  std::int64_t rejected_messages = 0;
  std::int64_t overruns = 0;
  std::int64_t utime = 0;  // wall-clock microseconds
};

// The state of run's last accepted step, written into msg: the positions of nodes (node
// indices), last's solver figures and muscle frame (lengths and velocities as step() computed
// them, not again), the contact of that state (empty without obstacles), notes. Every field is
// set; msg's vectors keep their storage, so that a message kept from step to step is filled
// without allocating.
void fill_state_message(tongue_lcm::lcmt_tongue_state& msg, const scene_run::SceneRun& run,
                        const std::vector<int>& nodes, const scene_run::StepResult& last,
                        const fem::ContactReport& contact, const StateNotes& notes);

}  // namespace tongue::server
