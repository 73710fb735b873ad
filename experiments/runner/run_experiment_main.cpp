// run_experiment EXPERIMENT.yaml [--logs DIR] [--port N] [--no-plots] [--quiet]
//
// Runs an experiment (experiment_file.hpp): starts lcm-logger, sim_server and the controllers as
// separate processes on one udpm bus, waits until the server has done the experiment's steps,
// stops everything cleanly (also when a process fails: it says which, and keeps what was
// logged), and collects the run file, the LCM log, every process's output, a summary and plots
// in DIR/<name>-<UTC time>/ (DIR defaults to logs).
//
// Exit status (common/exit_code.hpp): 0 completed; 1 bad command line, experiment or scene
// file, or a run that failed otherwise (a process ended badly, the wall-clock timeout; the
// summary says which); 2 the server published an unconverged step; 130 interrupted.
#include <cstdio>
#include <optional>
#include <string>

#include "common/exit_code.hpp"
#include "common/interrupt.hpp"
#include "common/number_text.hpp"
#include "experiment_file.hpp"
#include "experiment_run.hpp"

namespace {

void print_usage(std::FILE* to) {
  std::fprintf(to,
               "usage: run_experiment EXPERIMENT.yaml [--logs DIR] [--port N] [--no-plots] "
               "[--quiet]\n"
               "  --logs DIR   folder of the run folders (default logs)\n"
               "  --port N     udpm port of the run's bus (overrides the file's bus.port)\n"
               "  --no-plots   skip the plots\n"
               "  --quiet      no progress lines\n");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tongue::runner;
  using namespace tongue::common;
  std::string path;
  RunSettings settings;
  int port = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--help" || arg == "-h") {
      print_usage(stdout);
      return kExitOk;
    } else if (arg == "--logs" && has_value) {
      settings.root = argv[++i];
    } else if (arg == "--port" && has_value) {
      const std::optional<long long> p = parse_integer(argv[++i]);
      if (!p || *p < 1024 || *p > 65535) {
        std::fprintf(stderr, "run_experiment: --port must be in [1024, 65535]\n");
        return kExitError;
      }
      port = static_cast<int>(*p);
    } else if (arg == "--no-plots") {
      settings.plots = false;
    } else if (arg == "--quiet") {
      settings.progress = false;
    } else if (path.empty() && !arg.empty() && arg[0] != '-') {
      path = arg;
    } else {
      std::fprintf(stderr, "run_experiment: unexpected argument '%s'\n", arg.c_str());
      print_usage(stderr);
      return kExitError;
    }
  }
  if (path.empty()) {
    print_usage(stderr);
    return kExitError;
  }

  const InterruptHandlers interrupt;
  try {
    Experiment experiment = read_experiment(path);
    if (port != 0) experiment.port = port;
    if (settings.progress) {
      std::printf("experiment %s: %s on port %d\n", experiment.name.c_str(),
                  experiment.scene.filename().c_str(), experiment.port);
    }
    const RunOutcome outcome = run_experiment(experiment, settings, interrupt);
    std::fputs(outcome.summary.c_str(), stdout);
    if (!outcome.ok) {
      std::fprintf(stderr, "run_experiment: the run failed; everything is kept in %s\n",
                   outcome.folder.c_str());
    }
    return outcome.exit_code;
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "run_experiment: %s\n", ex.what());
    return kExitError;
  }
}
