#pragma once
// One run of an experiment: lcm-logger, sim_server and the controllers as separate processes on
// a bus of their own, watched until the server has done the experiment's steps (or something
// fails), stopped cleanly, and their results collected in a run folder with a summary and plots.
#include <filesystem>
#include <string>

#include "common/interrupt.hpp"
#include "experiment_file.hpp"

namespace tongue::runner {

struct RunSettings {
  std::filesystem::path root = "logs";  // run folders go under it
  bool plots = true;
  bool progress = true;  // a progress line on stdout about once a second
};

struct RunOutcome {
  bool ok = false;  // every process did its part and the server completed
  // The runner's exit status (common/exit_code.hpp): 0 ok; 2 the server published an
  // unconverged step; 130 interrupted; 1 any other failure (a process ended badly, a timeout).
  int exit_code = 1;
  std::filesystem::path folder;  // where everything was kept, also after a failure
  std::string summary;           // the text of summary.txt
};

// Throws scene::SceneError for a bad scene and std::runtime_error when the run cannot be set up
// (folder, programs); a failure during the run is reported in the outcome instead, with every
// file kept. A signal caught by interrupt ends the run early, cleanly.
RunOutcome run_experiment(const Experiment& experiment, const RunSettings& settings,
                          const common::InterruptHandlers& interrupt);

}  // namespace tongue::runner
