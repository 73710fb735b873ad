#include "experiment_run.hpp"

#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bus/channels.hpp"
#include "common/exit_code.hpp"
#include "project_programs.hpp"
#include "run_figures.hpp"
#include "run_folder.hpp"
#include "run_member.hpp"
#include "scene/scene_reader.hpp"
#include "state_watcher.hpp"

namespace tongue::runner {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The path of a program named in an experiment: one of this project's (built next to the runner),
// a path relative to the experiment's folder, or a name left to the PATH.
std::string resolve_program(const std::string& program, const fs::path& folder) {
  const auto& known = project_programs();
  if (const auto it = known.find(program); it != known.end()) return it->second;
  if (program.find('/') != std::string::npos) return (folder / program).lexically_normal();
  return program;
}

bool is_project_controller(const std::string& program) {
  return program != "sim_server" && project_programs().count(program) > 0;
}

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, fmt, a, b, c);
  return buffer;
}

// What a run is set up with before anything starts.
struct RunPlan {
  double dt = 0.0;  // s, the scene's step
  long steps = 0;   // the server's --max-steps
  std::string url;  // the experiment's own bus
  bus::Channels channels;
  fs::path folder;    // the run folder
  fs::path run_file;  // run.h5 in it, absolute
  fs::path bus_log;   // bus.lcmlog in it, absolute
};

// The experiment's scene, which must be a dynamic analysis.
scene::Scene read_dynamic_scene(const Experiment& e) {
  scene::Scene scene = scene::read_scene(e.scene.string());
  if (scene.analysis.type != scene::AnalysisType::dynamic) {
    throw scene::SceneError(e.scene.string(), "analysis.type", "an experiment needs dynamic");
  }
  return scene;
}

// The run folder under root, with copies of the experiment file and its scene.
fs::path prepare_run_folder(const Experiment& e, const fs::path& root) {
  fs::path folder = make_run_folder(root, e.name);
  fs::copy_file(e.file, folder / "experiment.yaml");
  fs::copy_file(e.scene, folder / "scene.yaml");
  return folder;
}

// The steps the experiment's duration makes, the run folder (created and filled with the
// copies) and the bus: the setup's order, so that a bad scene leaves no folder behind.
RunPlan plan_run(const Experiment& e, const RunSettings& settings) {
  const double dt = read_dynamic_scene(e).analysis.dt;
  const long steps = std::max(1L, std::lround(e.duration / dt));
  fs::path folder = prepare_run_folder(e, settings.root);
  std::string url = bus::default_lcm_url_on_port(e.port);
  bus::Channels channels(e.prefix);
  const fs::path run_file = fs::absolute(folder / "run.h5");
  const fs::path bus_log = fs::absolute(folder / "bus.lcmlog");
  return RunPlan{.dt = dt,
                 .steps = steps,
                 .url = std::move(url),
                 .channels = std::move(channels),
                 .folder = std::move(folder),
                 .run_file = run_file,
                 .bus_log = bus_log};
}

// The processes of a run.
struct Members {
  Member logger;
  Member server;
  std::vector<Member> controllers;
};

Member logger_member(const Experiment& e, const RunPlan& p) {
  return {"lcm-logger",
          {"lcm-logger", "--quiet", "--force", "--lcm-url=" + p.url, "--channel=" + e.prefix + ".*",
           p.bus_log.string()}};
}

Member server_member(const Experiment& e, const RunPlan& p) {
  Member server{"sim_server",
                {resolve_program("sim_server", e.folder()), e.scene.string(), "--lcm-url", p.url,
                 "--prefix", e.prefix, "--mode", e.server_mode, "--output", p.run_file.string(),
                 "--max-steps", std::to_string(p.steps)}};
  server.argv.insert(server.argv.end(), e.server_args.begin(), e.server_args.end());
  return server;
}

// A controller's own arguments, then the bus, the prefix and the steps; this project's
// controllers also get the server's mode.
Member controller_member(const ProcessSpec& c, const Experiment& e, const RunPlan& p) {
  Member m{c.name, {resolve_program(c.program, e.folder())}};
  m.argv.insert(m.argv.end(), c.args.begin(), c.args.end());
  for (const std::string& a : {std::string("--lcm-url"), p.url, std::string("--prefix"), e.prefix,
                               std::string("--max-steps"), std::to_string(p.steps)}) {
    m.argv.push_back(a);
  }
  if (is_project_controller(c.program)) {
    m.argv.push_back("--mode");
    m.argv.push_back(e.server_mode);
  }
  return m;
}

Members plan_members(const Experiment& e, const RunPlan& p) {
  Members members{logger_member(e, p), server_member(e, p), {}};
  for (const ProcessSpec& c : e.controllers) {
    members.controllers.push_back(controller_member(c, e, p));
  }
  return members;
}

// One run under way. The bus is watched before anything starts, so that state 0 cannot be
// missed.
struct Run {
  const Experiment& experiment;
  const RunSettings& settings;
  const common::InterruptHandlers& interrupt;
  const RunPlan plan;
  Members members;
  StateWatcher watcher;
  const Clock::time_point began;
};

// Starts lcm-logger and gives it the moment to subscribe; the failure, or "".
std::string start_logger(Run& r) {
  Member& logger = r.members.logger;
  start(logger, r.experiment.folder(), r.plan.folder);
  // lcm-logger subscribes right after opening its file; give it that moment.
  while (!fs::exists(r.plan.bus_log) && seconds_since(r.began) < 5.0 && logger.process->running()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  return logger.process->running() ? "" : "lcm-logger ended at start";
}

// Waits for the server's state 0; the failure, or "" once it is out.
std::string await_first_state(Run& r) {
  std::string failure;
  while (failure.empty() && !r.watcher.last_step()) {
    r.watcher.poll(50);
    if (!r.members.server.process->running()) failure = "sim_server ended before its first state";
    if (r.interrupt.raised()) failure = "interrupted";
    if (seconds_since(r.began) > r.experiment.timeout) {
      failure = "no state from sim_server within the timeout";
    }
  }
  return failure;
}

// Starts the logger (if the experiment keeps a log), the server, then the controllers; the
// failure, or "" when all are running.
std::string start_in_order(Run& r) {
  std::string failure;
  try {
    if (r.experiment.lcm_log) failure = start_logger(r);
    if (failure.empty()) start(r.members.server, r.experiment.folder(), r.plan.folder);
    // Controllers start once the server is up (its state 0 is out): they ask it to describe
    // itself, and the answer (model and current state) tells them where the loop stands.
    if (failure.empty()) failure = await_first_state(r);
    if (failure.empty()) {
      for (Member& c : r.members.controllers) start(c, r.experiment.folder(), r.plan.folder);
    }
  } catch (const std::exception& ex) {
    failure = ex.what();
  }
  return failure;
}

// The first controller that has failed the run by ending, or "".
std::string ended_controller_failure(Run& r) {
  // A controller may end once it has seen the last state (its --max-steps); before that, or
  // with an error, it has failed the run.
  const auto last_state_out = [&r] {
    return r.watcher.last_step() && *r.watcher.last_step() >= r.plan.steps;
  };
  for (Member& c : r.members.controllers) {
    if (c.process->running()) continue;
    c.status = c.process->status();
    // A controller that ended well saw the last state, which reached the watcher at the same
    // time; on a loaded machine the runner may look before reading it: a moment to do so.
    for (int i = 0; i < 20 && succeeded(*c.status) && !last_state_out(); ++i) r.watcher.poll(50);
    if (!(last_state_out() && succeeded(*c.status))) {
      return "controller '" + c.name + "' ended before the run was done (" +
             describe_status(*c.status) + ")";
    }
  }
  return "";
}

void print_progress(const Run& r) {
  std::printf("  step %lld of %ld (%.1f steps/s)\n",
              static_cast<long long>(r.watcher.last_step().value_or(0)), r.plan.steps,
              r.watcher.steps_per_second());
  std::fflush(stdout);
}

// Watches the run until the server ends or the run fails; the failure, or "".
std::string watch_until_done(Run& r) {
  std::string failure;
  double last_progress = 0.0;
  while (failure.empty()) {
    r.watcher.poll(50);
    if (!r.members.server.process->running()) break;
    failure = ended_controller_failure(r);
    if (r.experiment.lcm_log && !r.members.logger.process->running()) {
      failure = "lcm-logger ended during the run";
    }
    if (r.interrupt.raised()) failure = "interrupted";
    const double wall = seconds_since(r.began);
    if (wall > r.experiment.timeout) {
      failure = format("timeout: %.0f s of wall-clock time", r.experiment.timeout);
    }
    if (r.settings.progress && wall - last_progress >= 1.0) {
      last_progress = wall;
      print_progress(r);
    }
  }
  return failure;
}

// Stops the server first (its run file closes cleanly on SIGTERM), without a grace period when
// the run has failed; then the controllers, which end by themselves after the last state; then
// the logger once the last messages are in.
void stop_in_order(Run& r, bool failed) {
  stop(r.members.server, failed ? 0.0 : 10.0, SIGTERM, "SIGTERM");
  for (Member& c : r.members.controllers) stop(c, 2.0, SIGTERM, "SIGTERM");
  if (r.experiment.lcm_log) {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    stop(r.members.logger, 0.0, SIGINT, "SIGINT");
  }
}

// Once all are stopped: the server's bad exit, else the first controller that ended badly by
// itself, or "".
std::string exit_failure(const Members& members) {
  const Member& server = members.server;
  if (server.status && !succeeded(*server.status)) {
    return "sim_server ended with " + describe_status(*server.status) + " (see sim_server.err)";
  }
  for (const Member& c : members.controllers) {
    if (c.status && !succeeded(*c.status) && c.stopped_by.empty()) {
      return "controller '" + c.name + "' ended with " + describe_status(*c.status);
    }
  }
  return "";
}

void write_header(std::ostream& s, const Run& r) {
  const Experiment& e = r.experiment;
  s << "experiment " << e.name << " (" << e.file.string() << ")\n"
    << "run folder " << r.plan.folder.string() << "\n"
    << "scene " << e.scene.string() << format(", dt %g ms, %g s", 1e3 * r.plan.dt, e.duration)
    << " = " << r.plan.steps << " steps, " << e.server_mode << " mode, bus " << r.plan.url
    << ", prefix " << e.prefix << "\n";
}

std::string member_state(const Member& m) {
  if (!m.process) return "not started";
  return m.status ? describe_status(*m.status) : "still running";
}

// Each process's end and its command line: the server, the controllers, the logger.
void write_processes(std::ostream& s, const Run& r) {
  s << "\nprocesses (command lines; output in <name>.out and <name>.err):\n";
  std::vector<const Member*> all{&r.members.server};
  for (const Member& c : r.members.controllers) all.push_back(&c);
  if (r.experiment.lcm_log) all.push_back(&r.members.logger);
  for (const Member* m : all) {
    s << "  " << m->name << ": " << member_state(*m)
      << (m->stopped_by.empty() ? "" : ", stopped by the runner with " + m->stopped_by) << "\n"
      << "    " << quote(m->argv) << "\n";
  }
}

void write_landmarks(std::ostream& s, const std::vector<LandmarkMotion>& landmarks) {
  if (landmarks.empty()) return;
  s << "landmark displacement from the first frame [mm]:      dx       dy       dz   peak "
       "|d| at t [s]\n";
  for (const LandmarkMotion& m : landmarks) {
    char line[160];
    std::snprintf(line, sizeof line, "  %-20s %+8.3f %+8.3f %+8.3f %8.3f  %6.3f\n", m.name.c_str(),
                  m.final_mm[0], m.final_mm[1], m.final_mm[2], m.peak_mm, m.peak_time);
    s << line;
  }
}

// The run file's figures, the closed loop's pace and the landmarks' motion; the error reading
// the run file, or "".
std::string write_run_figures(std::ostream& s, const Run& r) {
  try {
    const RunFigures f = read_run_figures(r.plan.run_file);
    s << "\nrun file run.h5: status '" << f.status << "', " << f.steps << " steps, "
      << format("%.4g s simulated, physics %.2f s wall (real-time factor %.3g)", f.simulated,
                f.physics_wall, f.physics_wall > 0 ? f.simulated / f.physics_wall : 0.0)
      << ", " << f.newton_iterations << " Newton iterations, " << f.step_cuts << " step cuts\n";
    if (r.watcher.steps_per_second() > 0.0) {
      s << format(
          "closed loop: %.1f steps/s (%.3g simulated s per wall s), from the states seen "
          "on the bus\n",
          r.watcher.steps_per_second(), r.watcher.steps_per_second() * r.plan.dt);
    }
    write_landmarks(s, f.landmarks);
  } catch (const std::exception& ex) {
    s << "\nrun file: " << ex.what() << "\n";
    return ex.what();
  }
  return "";
}

void write_bus_figures(std::ostream& s, const Run& r) {
  const bus::Channels& channels = r.plan.channels;
  if (const auto b = read_bus_figures(r.plan.bus_log, channels.state, channels.activation)) {
    s << "LCM log bus.lcmlog: " << b->states << " states, " << b->activations << " activations";
    if (b->repeated_activations > 0) s << " and " << b->repeated_activations << " repeats of them";
    s << " (replay: lcm-logplayer --lcm-url='" << r.plan.url << "' bus.lcmlog)\n";
  } else {
    s << "LCM log bus.lcmlog: cannot be read\n";
  }
}

std::vector<std::string> plot_command(const Run& r) {
  std::vector<std::string> argv{kSystemPython, kPlotScript, r.plan.run_file.string(), "--out",
                                fs::absolute(r.plan.folder).string()};
  if (!r.experiment.plot_times.empty()) {
    argv.push_back("--times");
    for (const double t : r.experiment.plot_times) argv.push_back(format("%g", t));
  }
  return argv;
}

// Runs the plot script on the run file and writes how it went; the failure, or "".
std::string make_plots(std::ostream& s, const Run& r) {
  Member plots{"plots", plot_command(r)};
  try {
    start(plots, r.plan.folder, r.plan.folder);
    stop(plots, 120.0, SIGTERM, "SIGTERM");
    const bool written = succeeded(*plots.status);
    s << "plots: "
      << (written ? "written" : "FAILED (" + describe_status(*plots.status) + ", see plots.err)")
      << "\n";
    return written ? "" : "plots failed";
  } catch (const std::exception& ex) {
    s << "plots: " << ex.what() << "\n";
    return ex.what();
  }
}

// What the summary's figures found wrong, each "" when nothing.
struct Findings {
  std::string figures_error;  // the run file cannot be read
  std::string plot_failure;
};

// The summary up to its result line.
Findings write_summary(std::ostream& s, const Run& r, double wall) {
  write_header(s, r);
  write_processes(s, r);
  s << format("wall time %.2f s", wall) << "\n";
  Findings found;
  found.figures_error = write_run_figures(s, r);
  if (r.experiment.lcm_log) write_bus_figures(s, r);
  if (r.settings.plots && found.figures_error.empty()) found.plot_failure = make_plots(s, r);
  return found;
}

// The run's failure: the first of the run's own, the plots' and the run file's, or "".
std::string judge(const std::string& run_failure, const Findings& found) {
  if (!run_failure.empty()) return run_failure;
  if (!found.plot_failure.empty()) return found.plot_failure;
  if (!found.figures_error.empty()) return "the run file cannot be read";
  return "";
}

// The runner's exit status for the run (see RunOutcome::exit_code).
int exit_code(const Run& r, bool ok) {
  const std::optional<int>& server = r.members.server.status;
  const bool unconverged =
      r.watcher.any_unconverged() ||
      (server && WIFEXITED(*server) && WEXITSTATUS(*server) == common::kExitNotConverged);
  return ok                     ? common::kExitOk
         : r.interrupt.raised() ? common::kExitInterrupted
         : unconverged          ? common::kExitNotConverged
                                : common::kExitError;
}

}  // namespace

RunOutcome run_experiment(const Experiment& e, const RunSettings& settings,
                          const common::InterruptHandlers& interrupt) {
  const RunPlan plan = plan_run(e, settings);
  Run r{e,
        settings,
        interrupt,
        plan,
        plan_members(e, plan),
        StateWatcher(plan.url, plan.channels.state),
        Clock::now()};

  std::string failure = start_in_order(r);
  if (failure.empty()) failure = watch_until_done(r);
  stop_in_order(r, !failure.empty());
  const double wall = seconds_since(r.began);
  if (failure.empty()) failure = exit_failure(r.members);

  std::ostringstream s;
  failure = judge(failure, write_summary(s, r, wall));
  s << "\nresult: " << (failure.empty() ? "completed" : "FAILED: " + failure) << "\n";

  RunOutcome outcome;
  outcome.folder = r.plan.folder;
  outcome.ok = failure.empty();
  outcome.exit_code = exit_code(r, outcome.ok);
  outcome.summary = s.str();
  std::ofstream(outcome.folder / "summary.txt") << outcome.summary;
  return outcome;
}

}  // namespace tongue::runner
