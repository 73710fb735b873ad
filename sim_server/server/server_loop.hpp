#pragma once
// The tongue server's loop: a dynamic scene with muscles advanced step by step under activation
// messages, publishing its state after every step and logging it to the run file.
//
// Lock-step mode: the state of step k is published; the loop advances to k + 1 when the
// activation tagged k + 1 arrives (any other step number is rejected and counted). Without one
// for timeout_ms, it reports the silence on stderr and holds (keeps waiting) or stops. With
// several controllers (ServerOptions::controllers = N), it advances once N accepted messages
// tagged k + 1 have arrived, merged (ActivationRound: each names its own muscles; one naming a
// muscle already set for k + 1 is rejected whole); the silence report says how many arrived.
// Fast mode: free-running, every step uses the latest accepted activation (zero-order hold; any
// step number is accepted, -1 included).
// Real-time mode: as fast mode, but paced to a steady clock: counting from the clock's anchor
// (the start, a resume or a reset), step n + 1 starts no earlier than anchor + n dt; a step that
// finishes after anchor + (n + 1) dt is an overrun (counted in the state's overruns; late steps
// are not skipped, the loop catches up). After silence_s without a valid activation it holds,
// decays (all levels to 0) or stops, reported once per silence.
// States carry all nodes or a subset (Nodes); in fast and real-time mode every publish_every-th
// step is published (every step is logged).
// Commands: pause, resume, reset (initial state, step 0, all activations 0, counters cleared),
// shutdown (clean end), describe (the model again, then the current state).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "bus/messages.hpp"
#include "fem/assembly/ellipticity_monitor.hpp"
#include "fem/integrator/newmark_integrator.hpp"
#include "run_file/run_file_writer.hpp"
#include "scene/scene.hpp"
#include "scene/scene_builder.hpp"
#include "server/activation_round.hpp"
#include "server/server_bus.hpp"

namespace tongue::server {

enum class Mode { lockstep, fast, realtime };
enum class OnSilence { hold, stop, decay };  // decay: real-time mode only
// Nodes whose positions the states carry: all; the mesh's boundary (fem::boundary_nodes); its
// "midsagittal" node set; its landmarks (the first node of each landmark set present, as listed
// in the model message).
enum class Nodes { all, surface, midsagittal, landmarks };

struct ServerOptions {
  Mode mode = Mode::lockstep;
  int timeout_ms = 1000;  // lock-step: silence before a report (and a stop with OnSilence::stop)
  // Lock-step: accepted activation messages tagged k + 1 that make step k + 1 (one per
  // controller, each naming its own muscles). Other modes: 1.
  int controllers = 1;
  OnSilence on_silence = OnSilence::hold;
  double silence_s = 0.5;  // real-time: silence before hold / decay / stop [s]
  Nodes nodes = Nodes::all;
  int publish_every = 1;  // fast and real-time: publish the state every this many steps
  std::optional<std::int64_t> max_steps;  // end (exit 0) once this step is reached
  std::string output;                     // run file; empty: none
};

// How the loop ended; the process exit status.
enum class ExitStatus : int {
  ok = 0,             // shutdown command, or max_steps reached
  error = 1,          // an exception (e.g. the run file cannot be written)
  not_converged = 2,  // a step failed to converge even after cuts
  silence = 3,        // on_silence stop: no activation within timeout_ms (real-time: silence_s)
  interrupted = 130,  // SIGINT / SIGTERM (the stop predicate)
};

class ServerLoop {
 public:
  // Throws std::invalid_argument when the scene is not dynamic, has no muscles, or its mesh
  // lacks the node sets options.nodes asks for; or when options are out of range.
  // stop_requested is polled between messages and steps (e.g. a signal flag).
  ServerLoop(const scene::Scene& scene, scene::BuiltScene built, ServerBus& bus,
             ServerOptions options, std::function<bool()> stop_requested);
  ~ServerLoop();
  ServerLoop(const ServerLoop&) = delete;
  ServerLoop& operator=(const ServerLoop&) = delete;

  // Settles if the scene says so, publishes the model and state 0, and runs until shutdown,
  // max_steps, failure, silence (with stop) or stop_requested. Sets the run file's status.
  ExitStatus run();

  std::int64_t step() const { return step_; }

 private:
  bool initialize();  // settle (once) and start from the initial state; false: settling failed
  void restart();     // integrator at the initial state, step 0, activations 0
  bool advance(const fem::Vector& levels);  // one dt with levels; false when not converged
  void handle(const IncomingMessage& message);
  void handle_activation(const IncomingMessage& message);
  void handle_command(const IncomingMessage& message);
  void reject(const std::string& kind, const std::string& reason);
  void publish_model();
  void publish_state(const std::string& status, bool converged = true);
  void log_frame();
  ExitStatus loop();
  void anchor_clock();             // real-time: the next step starts now, later ones dt apart
  double step_start_time() const;  // real-time: steady-clock s at which step_ + 1 may start
  bool should_publish() const;     // fast and real-time: whether step_'s state is published
  std::string silence_text() const;
  std::string lockstep_wait_text() const;  // what lock-step waits for: the step, m of N arrived

  const scene::Scene& scene_;
  scene::BuiltScene built_;
  ServerBus& bus_;
  ServerOptions options_;
  std::function<bool()> stop_requested_;
  std::unique_ptr<run_file::RunFileWriter> log_;
  std::unique_ptr<fem::NewmarkIntegrator> integrator_;
  fem::EllipticityMonitor ellipticity_{*built_.solid};  // warns once when the law turns unstable
  fem::Vector initial_u_;                // m, the state step 0 starts from (settled or rest)
  fem::Vector accepted_u_, accepted_v_;  // m, m/s: the last accepted step's state
  fem::Vector levels_;                   // [1] activations held (fast) / of the last step
  // Lock-step: the messages accepted for step_ + 1 so far, merged; complete only while paused
  // (a complete round is applied at once otherwise, and on resume).
  ActivationRound round_;
  std::vector<std::string> muscle_names_;
  std::vector<int> node_indices_;  // nodes the states carry
  std::int64_t step_ = 0;
  double time_ = 0.0;  // s
  std::int64_t rejected_ = 0;
  std::int64_t overruns_ = 0;
  double anchor_time_ = 0.0;             // real-time: steady-clock s of the clock's anchor
  std::int64_t anchor_step_ = 0;         // real-time: step_ at the anchor
  double last_activation_ = 0.0;         // real-time: steady-clock s of the last valid activation
  bool silent_ = false;                  // real-time: the current silence has been reported
  double last_overrun_report_ = -1e300;  // steady-clock s
  std::int64_t unreported_overruns_ = 0;
  bool paused_ = false;
  bool shutdown_ = false;
  int resets_ = 0;
  fem::StepReport last_report_;
  std::string failure_;
  std::map<std::string, double> last_reported_;  // reject kind -> steady-clock s of last report
  std::map<std::string, int> unreported_;        // reject kind -> rejections since that report
};

}  // namespace tongue::server
