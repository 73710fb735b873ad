#pragma once
// SIGINT and SIGTERM as a flag the control loop polls: while an InterruptHandlers object lives,
// either signal sets the flag (and interrupts the bus wait, no SA_RESTART) instead of killing the
// process, so that the controller ends cleanly with its summary. The previous handlers come back
// when it is destroyed.
#include <csignal>

namespace tongue::controller {

class InterruptHandlers {
 public:
  InterruptHandlers();
  ~InterruptHandlers();
  InterruptHandlers(const InterruptHandlers&) = delete;
  InterruptHandlers& operator=(const InterruptHandlers&) = delete;

  // True once SIGINT or SIGTERM has arrived since construction.
  bool raised() const;
  // The signal that arrived (SIGINT or SIGTERM), 0 when none.
  int signal_number() const;

 private:
  struct sigaction previous_int_ {};
  struct sigaction previous_term_ {};
};

}  // namespace tongue::controller
