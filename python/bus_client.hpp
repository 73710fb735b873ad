#pragma once
// A controller's connection to a tongue server from Python: the controllers' own session
// (controller::ControlSession, the same protocol, timeouts and exit codes as the C++
// controllers), handed out one state at a time so that a Python for-loop can drive it. This class
// holds everything but the Python types; bus_client_bindings.cpp converts.
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "controller/command_line.hpp"
#include "controller/control_session.hpp"

namespace tongue::python {

class BusClient {
 public:
  // Starts receiving on the server's channels. Throws std::runtime_error naming the URL when LCM
  // cannot be opened.
  BusClient(const std::string& program, const controller::CommonOptions& options);

  // The model, waited for (sending "describe" while none comes); nullptr when the session ended
  // (outcome() says why). stop is asked between waits of at most 50 ms.
  const controller::Model* connect(const controller::ControlSession::StopCheck& stop);
  // The next new state, in order; nullopt when the session ended. The last state of each batch
  // the server published awaits an answer (send) before the next call; earlier ones in a batch
  // (after a reset, or queued while the caller was busy) need none.
  std::optional<controller::State> next(const controller::ControlSession::StopCheck& stop);
  // The levels for the step after the state last handed out. Nothing is sent for a state that a
  // later one already follows, nor after the session's last state. Throws std::logic_error when
  // that state was answered already.
  void send(const controller::MuscleLevels& levels);

  const controller::Model* model() const { return model_; }
  // Whether the state last handed out awaits an answer.
  bool awaiting_answer() const { return awaiting_ && queued_.empty(); }
  const controller::LoopOutcome& outcome() const { return session_.outcome(); }
  const controller::CommonOptions& options() const { return session_.options(); }
  void fail(const std::string& what) { session_.fail(what); }
  void end_after(std::int64_t step, const std::string& reason) { session_.end_after(step, reason); }
  // The controllers' summary line (control_loop.hpp), with the caller's own figures after it.
  std::string summary(const std::string& controller_summary) const;

 private:
  // The session asks stop through this, so that each call can bring its own.
  const controller::ControlSession::StopCheck* stop_ = nullptr;
  std::string program_;
  controller::ControlSession session_;
  const controller::Model* model_ = nullptr;
  std::deque<controller::State> queued_;   // of the batch being handed out
  std::optional<controller::State> last_;  // the state last handed out
  bool awaiting_ = false;  // the batch being handed out awaits an answer after its last state
};

// The controllers' command line (controller/command_line.hpp) for a Python controller: throws
// controller::UsageError as the C++ programs do.
controller::CommandLine parse_controller_command_line(const std::vector<std::string>& args,
                                                      const std::vector<std::string>& options);

}  // namespace tongue::python
