#pragma once
// The tongue server's loop: a dynamic scene with muscles advanced step by step under activation
// messages, publishing its state after every step and logging it to the run file.
//
// Lock-step mode: the state of step k is published; the loop advances to k + 1 when the
// activation tagged k + 1 arrives (any other step number is rejected and counted). Without one
// for timeout_ms, it reports the silence on stderr and holds (keeps waiting) or stops.
// Fast mode: free-running, every step uses the latest accepted activation (zero-order hold; any
// step number is accepted, -1 included).
// Commands: pause, resume, reset (initial state, step 0, all activations 0, counters cleared),
// shutdown (clean end), describe (the model again).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "bus/messages.hpp"
#include "fem/integrator/newmark_integrator.hpp"
#include "logging/position_log.hpp"
#include "scene/scene.hpp"
#include "scene/scene_builder.hpp"
#include "server/server_bus.hpp"

namespace tongue::server {

enum class Mode { lockstep, fast };
enum class OnSilence { hold, stop };

struct ServerOptions {
  Mode mode = Mode::lockstep;
  int timeout_ms = 1000;  // lock-step: silence before a report (and a stop with OnSilence::stop)
  OnSilence on_silence = OnSilence::hold;
  std::optional<std::int64_t> max_steps;  // end (exit 0) once this step is reached
  std::string output;                     // run file; empty: none
};

// How the loop ended; the process exit status.
enum class ExitStatus : int {
  ok = 0,             // shutdown command, or max_steps reached
  error = 1,          // an exception (e.g. the run file cannot be written)
  not_converged = 2,  // a step failed to converge even after cuts
  silence = 3,        // lock-step, on_silence stop: no activation within timeout_ms
  interrupted = 130,  // SIGINT / SIGTERM (the stop predicate)
};

class ServerLoop {
 public:
  // Throws std::invalid_argument when the scene is not dynamic or has no muscles.
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

  const scene::Scene& scene_;
  scene::BuiltScene built_;
  ServerBus& bus_;
  ServerOptions options_;
  std::function<bool()> stop_requested_;
  std::unique_ptr<logging::PositionLog> log_;
  std::unique_ptr<fem::NewmarkIntegrator> integrator_;
  fem::Vector initial_u_;                // m, the state step 0 starts from (settled or rest)
  fem::Vector accepted_u_, accepted_v_;  // m, m/s: the last accepted step's state
  fem::Vector levels_;                   // [1] activations held (fast) / of the last step
  std::optional<fem::Vector> pending_;   // lock-step: accepted levels for step + 1 (while paused)
  std::vector<std::string> muscle_names_;
  std::int64_t step_ = 0;
  double time_ = 0.0;  // s
  std::int64_t rejected_ = 0;
  bool paused_ = false;
  bool shutdown_ = false;
  int resets_ = 0;
  fem::StepReport last_report_;
  std::string failure_;
  std::map<std::string, double> last_reported_;  // reject kind -> steady-clock s of last report
  std::map<std::string, int> unreported_;        // reject kind -> rejections since that report
};

}  // namespace tongue::server
