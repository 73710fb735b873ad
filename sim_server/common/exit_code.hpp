#pragma once
// The exit status of every program of the project (docs/exit_codes.md). A code means the same
// in every program, so that a script or the experiment runner reads any of them alike.
namespace tongue::common {

enum ExitCode : int {
  kExitOk = 0,
  kExitError = 1,          // bad command line, bad input file or mesh, bus or I/O error
  kExitNotConverged = 2,   // a step (or load increment) failed to converge, even after cuts
  kExitSilence = 3,        // stopped on silence: no activation (server) or no state in time
  kExitTimeout = 4,        // a controller's wait for the server's model or state timed out
  kExitRejected = 5,       // the server rejected a controller's activation (a rejection notice)
  kExitInterrupted = 130,  // SIGINT or SIGTERM (the shell's 128 + SIGINT)
};

}  // namespace tongue::common
