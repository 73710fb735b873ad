#pragma once
// SIGINT and SIGTERM as a flag that a program's loop polls: while an InterruptHandlers object
// lives, either signal sets the flag instead of killing the process, so that the program ends
// cleanly (closing its run file, printing its summary) with kExitInterrupted or its own outcome.
// No SA_RESTART: a blocking wait (the LCM bus, a sleep) returns at once and the loop sees the
// flag. The previous handlers come back when the object is destroyed.
#include <csignal>

namespace tongue::common {

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
  // "SIGINT" or "SIGTERM" for messages; empty when none arrived.
  const char* signal_name() const;

 private:
  struct sigaction previous_int_ {};
  struct sigaction previous_term_ {};
};

}  // namespace tongue::common
