#pragma once
// The tongue server's loop: a dynamic scene with muscles advanced step by step under activation
// messages, publishing its state after every step and logging it to the run file.
//
// Lock-step mode: the state of step k is published; the loop advances to k + 1 when the
// activation tagged k + 1 arrives (any other step number is rejected and counted). Without one
// for timeout_ms, it reports the silence on stderr and holds (keeps waiting) or stops. With
// several controllers (ServerOptions::controllers = N), it advances once N accepted messages
// tagged k + 1 have arrived, merged (ActivationRound: each names its own muscles; one naming a
// muscle already set for k + 1 is rejected whole); the silence report says how many arrived,
// and how many for k + 1 were rejected. Every rejected activation that could be decoded is also
// answered by a rejection notice on the bus, for its sender. Over a lossy bus: while the
// activations for k + 1 are late, the state of step k is published again (StateRepeater), and a
// sender's unchanged repeat of a message already taken is ignored (RoundSenders), so that a lost
// state or activation costs a delay and the run is the same as without the loss.
// Fast mode: free-running, every step uses the latest accepted activation (zero-order hold; any
// step number is accepted, -1 included).
// Real-time mode: as fast mode, but paced to a steady clock: counting from the clock's anchor
// (the start, a resume or a reset), step n + 1 starts no earlier than anchor + n dt; a step that
// finishes after anchor + (n + 1) dt is an overrun (counted in the state's overruns; late steps
// are not skipped, the loop catches up). After silence_s without a valid activation it holds,
// decays (all levels to 0) or stops, reported once per silence.
// States carry all nodes or a subset (Nodes); in fast and real-time mode every publish_every-th
// step is published (every step is logged).
// Commands: pause (a complete lock-step round then waits for resume), resume, reset (initial
// state, step 0, all activations 0, counters cleared), shutdown (clean end), describe (the model
// again, then the current state). Rejections and overruns are reported on stderr at most once
// per kind per second, with the count of those not shown.
// The run file's root attributes: status ("completed", "interrupted", "stopped: <silence>",
// "failed: <why>"), resets (how many), material_warning (the first loss of ellipticity), the
// steps' timing (StepTiming::attributes), also summed up in one line on stderr at the end, and in
// lock-step repeated_states and repeated_activations (how many of each the loss recovery made).
//
// How it is built: the loop takes the messages one at a time and hands each to ControlInput,
// which only records what it means (an activation merged into the round or the hold, a command
// pending, a rejection counted); the loop alone then decides whether a step is due, and steps,
// logs and publishes. SceneRun does the physics; take_step() is its one caller. After the
// physics a step publishes its state first, so that in lock-step the controller's turn overlaps
// the rest (the run file's frame, the bookkeeping); the state message and the frame's positions
// are kept from step to step, so that a step allocates nothing for them.
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bus/command.hpp"
#include "bus/server_bus.hpp"
#include "common/rate_limited_reporter.hpp"
#include "run_file/run_file_queue.hpp"
#include "scene/scene.hpp"
#include "scene/scene_builder.hpp"
#include "scene_run/scene_run.hpp"
#include "server/control_input.hpp"
#include "server/node_selection.hpp"
#include "server/server_options.hpp"
#include "server/state_repeater.hpp"
#include "server/step_timing.hpp"

namespace tongue::server {

class ServerLoop {
 public:
  // Throws std::invalid_argument when the scene is not dynamic, has no muscles, or its mesh
  // lacks the node sets options.nodes asks for; or when options are out of range.
  // stop_requested is polled between messages and steps (e.g. a signal flag).
  ServerLoop(const scene::Scene& scene, scene::BuiltScene built, bus::ServerBus& bus,
             ServerOptions options, std::function<bool()> stop_requested);
  ~ServerLoop();
  ServerLoop(const ServerLoop&) = delete;
  ServerLoop& operator=(const ServerLoop&) = delete;

  // Settles if the scene says so, publishes the model and state 0, and runs until shutdown,
  // max_steps, failure, silence (with stop) or stop_requested. Sets the run file's status.
  ExitStatus run();

  std::int64_t step() const { return run_.step_count(); }

 private:
  // The schedule.
  ExitStatus loop();
  std::optional<ExitStatus> ending() const;   // why the loop ends now, if it does
  int wait_ms() const;                        // how long the next receive may wait
  const fem::Vector* due_levels() const;      // the levels of a step due now, or null
  std::optional<ExitStatus> watch_silence();  // reports silence; common::kExitSilence: stop
  void repeat_state();     // lock-step: the state again when the next step's activations are late
  void publish_notices();  // the rejection notices of the message just recorded
  void anchor_clock();     // real-time: the next step starts now, later ones dt apart
  double step_start_time() const;  // real-time: steady-clock s at which the next step may start
  bool should_publish() const;     // fast and real-time: whether the current state is published

  // What the loop does.
  bool start();  // settles (once) and clears to step 0; false: settling failed
  void clear_to_step_zero();
  void execute(bus::Command command);
  void take_step(const fem::Vector& levels);
  void count_overrun(double late);  // real-time: late [s] > 0 is an overrun
  void warn_material(const scene_run::EllipticityFinding& found);  // stderr and run file
  void warn_reduced(const std::string& warning);                   // stderr and run file
  void publish_model();
  void publish_state(const std::string& status, bool converged = true);
  void log_frame();
  // The contact of the last accepted state, found at its first use.
  const fem::ContactReport& contact();
  std::string status_text(ExitStatus status) const;  // the run file's status attribute
  std::string silence_text() const;
  std::string lockstep_wait_text() const;  // what lock-step waits for: the step, m of N arrived

  scene_run::SceneRun run_;
  bus::ServerBus& bus_;
  ServerOptions options_;
  std::function<bool()> stop_requested_;
  std::unique_ptr<run_file::RunFileQueue> log_;
  std::vector<int> node_indices_;  // nodes the states carry
  common::RateLimitedReporter step_reports_;
  StepTiming timing_;
  StateRepeater repeater_;

  std::deque<bus::IncomingMessage> inbox_;  // received, not yet recorded
  ControlInput input_;                      // what the messages recorded so far ask for
  // The last step's solver figures and muscle frame (at step 0: none, and the initial frame),
  // published again by pause, describe and reset without computing them twice.
  scene_run::StepResult last_;
  // The contact of the last accepted state (empty without obstacles), found once for its state
  // messages and its run-file frame, and only when one of them is made; none: not yet found.
  std::optional<fem::ContactReport> contact_;
  // Kept from step to step, so that a step's state message and run-file frame reuse storage.
  tongue_lcm::lcmt_tongue_state state_;
  fem::Vector positions_;  // m, the frame's node positions

  std::int64_t overruns_ = 0;
  int resets_ = 0;
  bool paused_ = false;
  bool shutdown_ = false;
  std::string failure_;
  double deadline_ = 0.0;         // lock-step: steady-clock s at which silence is reported
  double anchor_time_ = 0.0;      // real-time: steady-clock s of the clock's anchor
  std::int64_t anchor_step_ = 0;  // real-time: the step at the anchor
  bool silent_ = false;           // real-time: the current silence has been reported
};

}  // namespace tongue::server
