#pragma once
// An experiment file: which scene the server runs, for how long, which controllers drive it and
// how the run is recorded. YAML schema (paths relative to the experiment file's folder, which is
// also the working directory of every process the runner starts):
//
//   name: ai                        # required; the run folder is logs/<name>-<UTC time>/
//   scene: ../scenes/tongue_ep.yaml # required; a dynamic scene with muscles
//   duration: 0.4                   # required; simulated time [s], rounded to whole steps
//   bus: {port: 7667, prefix: TONGUE_}          # optional; udpm on the loopback, ttl 0
//   server: {mode: lockstep, args: [--nodes, all]}   # optional; sim_server's extra options
//   controllers:                    # required, at least one
//     - name: ep                    # unique, [A-Za-z0-9_-]; names its output files
//       program: ep_controller      # a program of this project, a path, or a name on the PATH
//       args: [--plan, ../controllers/plans/ai.yaml]
//   lcm_log: true                   # optional (default true): record the bus with lcm-logger
//   plots: {times: [0.0, 0.15, 0.3]}   # optional; shape snapshots [s] (default: the script's)
//   timeout: 600                    # optional; wall-clock limit of the run [s] (default 600)
//
// Every controller is started with --lcm-url, --prefix and --max-steps appended (the project's
// controllers also get --mode); other programs must accept those three.
#include <filesystem>
#include <string>
#include <vector>

#include "common/key_path_error.hpp"

namespace tongue::runner {

struct ProcessSpec {
  std::string name;
  std::string program;
  std::vector<std::string> args;
};

struct Experiment {
  std::string name;
  std::filesystem::path file;   // the experiment file, absolute
  std::filesystem::path scene;  // absolute
  double duration = 0.0;        // s
  int port = 7667;
  std::string prefix = "TONGUE_";
  std::string server_mode = "lockstep";
  std::vector<std::string> server_args;
  std::vector<ProcessSpec> controllers;
  bool lcm_log = true;
  std::vector<double> plot_times;  // s; empty: the plot script's default
  double timeout = 600.0;          // s of wall-clock time

  std::filesystem::path folder() const { return file.parent_path(); }
};

// Reads and checks the file (keys, types, ranges, that the scene file exists); the scene itself
// is checked by the scene reader. Throws common::KeyPathError naming the file and the key.
Experiment read_experiment(const std::filesystem::path& path);

}  // namespace tongue::runner
