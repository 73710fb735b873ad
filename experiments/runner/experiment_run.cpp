#include "experiment_run.hpp"

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/channels.hpp"
#include "bus/messages.hpp"
#include "child_process.hpp"
#include "common/exit_code.hpp"
#include "project_programs.hpp"
#include "run_figures.hpp"
#include "run_folder.hpp"
#include "scene/scene_reader.hpp"

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

// A process of the run with the name the summary gives it.
struct Member {
  Member(std::string n, std::vector<std::string> a) : name(std::move(n)), argv(std::move(a)) {}
  std::string name;
  std::vector<std::string> argv;
  std::unique_ptr<ChildProcess> process;
  std::optional<int> status;  // wait status once ended
  std::string stopped_by;     // the signal the runner sent, if it had to stop it
};

// Starts a member with its output to <name>.out / <name>.err in the run folder.
void start(Member& m, const fs::path& workdir, const fs::path& folder) {
  m.process = std::make_unique<ChildProcess>(m.argv, workdir, folder / (m.name + ".out"),
                                             folder / (m.name + ".err"));
}

// Ends a member still running: waits grace_s, then sends sig and waits again, then SIGKILL.
void stop(Member& m, double grace_s, int sig, const char* sig_name) {
  if (!m.process) return;
  if (!m.status) m.status = m.process->wait(grace_s);
  if (!m.status) {
    m.stopped_by = sig_name;
    m.process->signal(sig);
    m.status = m.process->wait(10.0);
  }
  if (!m.status) {
    m.stopped_by = "SIGKILL";
    m.process->signal(SIGKILL);
    m.status = m.process->wait(5.0);
  }
}

std::string quote(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) {
    if (!s.empty()) s += ' ';
    const bool plain = a.find_first_of(" '\"&?;*") == std::string::npos && !a.empty();
    s += plain ? a : "'" + a + "'";
  }
  return s;
}

// Watches the server's states: readiness (state 0), progress and the closed loop's pace.
class StateWatcher {
 public:
  StateWatcher(const std::string& url, const std::string& channel) : lcm_(url) {
    if (!lcm_.good()) throw std::runtime_error("cannot open the LCM bus " + url);
    lcm_.subscribe(channel, &StateWatcher::on_state, this);
  }
  void poll(int timeout_ms) { lcm_.handleTimeout(timeout_ms); }
  std::optional<std::int64_t> last_step() const { return last_step_; }
  // Steps per wall second between the first and the last state received (0: too few).
  double steps_per_second() const {
    const double span = std::chrono::duration<double>(last_at_ - first_at_).count();
    return (driving_ && *last_step_ > first_step_ && span > 0.0)
               ? static_cast<double>(*last_step_ - first_step_) / span
               : 0.0;
  }
  bool any_unconverged() const { return unconverged_; }

 private:
  void on_state(const lcm::ReceiveBuffer*, const std::string&,
                const tongue_lcm::lcmt_tongue_state* s) {
    // The pace counts from the first step the controllers drove (state 0 comes before they
    // start).
    if (s->step >= 1 && !driving_) {
      driving_ = true;
      first_step_ = s->step;
      first_at_ = Clock::now();
    }
    last_step_ = s->step;
    last_at_ = Clock::now();
    if (!s->converged) unconverged_ = true;
  }

  lcm::LCM lcm_;
  std::optional<std::int64_t> last_step_;
  bool driving_ = false;
  std::int64_t first_step_ = 0;
  Clock::time_point first_at_, last_at_;
  bool unconverged_ = false;
};

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, fmt, a, b, c);
  return buffer;
}

}  // namespace

RunOutcome run_experiment(const Experiment& e, const RunSettings& settings,
                          const common::InterruptHandlers& interrupt) {
  const scene::Scene scene = scene::read_scene(e.scene.string());
  if (scene.analysis.type != scene::AnalysisType::dynamic) {
    throw scene::SceneError(e.scene.string(), "analysis.type", "an experiment needs dynamic");
  }
  const double dt = scene.analysis.dt;
  const long steps = std::max(1L, std::lround(e.duration / dt));

  RunOutcome outcome;
  outcome.folder = make_run_folder(settings.root, e.name);
  const fs::path& folder = outcome.folder;
  fs::copy_file(e.file, folder / "experiment.yaml");
  fs::copy_file(e.scene, folder / "scene.yaml");

  const std::string url = bus::default_lcm_url_on_port(e.port);
  const bus::Channels channels(e.prefix);
  const fs::path run_file = fs::absolute(folder / "run.h5");
  const fs::path bus_log = fs::absolute(folder / "bus.lcmlog");

  Member logger{"lcm-logger",
                {"lcm-logger", "--quiet", "--force", "--lcm-url=" + url,
                 "--channel=" + e.prefix + ".*", bus_log.string()}};
  Member server{"sim_server",
                {resolve_program("sim_server", e.folder()), e.scene.string(), "--lcm-url", url,
                 "--prefix", e.prefix, "--mode", e.server_mode, "--output", run_file.string(),
                 "--max-steps", std::to_string(steps)}};
  server.argv.insert(server.argv.end(), e.server_args.begin(), e.server_args.end());
  std::vector<Member> controllers;
  for (const ProcessSpec& c : e.controllers) {
    Member m{c.name, {resolve_program(c.program, e.folder())}};
    m.argv.insert(m.argv.end(), c.args.begin(), c.args.end());
    for (const std::string& a : {std::string("--lcm-url"), url, std::string("--prefix"), e.prefix,
                                 std::string("--max-steps"), std::to_string(steps)}) {
      m.argv.push_back(a);
    }
    if (is_project_controller(c.program)) {
      m.argv.push_back("--mode");
      m.argv.push_back(e.server_mode);
    }
    controllers.push_back(std::move(m));
  }

  // The bus is watched before anything starts, so that state 0 cannot be missed.
  StateWatcher watcher(url, channels.state);
  std::string failure;
  const Clock::time_point began = Clock::now();
  try {
    if (e.lcm_log) {
      start(logger, e.folder(), folder);
      // lcm-logger subscribes right after opening its file; give it that moment.
      while (!fs::exists(bus_log) && seconds_since(began) < 5.0 && logger.process->running()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      if (!logger.process->running()) failure = "lcm-logger ended at start";
    }
    if (failure.empty()) start(server, e.folder(), folder);
    // Controllers start once the server is up (its state 0 is out): they ask it to describe
    // itself, and the answer (model and current state) tells them where the loop stands.
    while (failure.empty() && !watcher.last_step()) {
      watcher.poll(50);
      if (!server.process->running()) failure = "sim_server ended before its first state";
      if (interrupt.raised()) failure = "interrupted";
      if (seconds_since(began) > e.timeout) failure = "no state from sim_server within the timeout";
    }
    if (failure.empty()) {
      for (Member& c : controllers) start(c, e.folder(), folder);
    }
  } catch (const std::exception& ex) {
    failure = ex.what();
  }

  double last_progress = 0.0;
  while (failure.empty()) {
    watcher.poll(50);
    if (!server.process->running()) break;
    // A controller may end once it has seen the last state (its --max-steps); before that, or
    // with an error, it has failed the run.
    const bool last_state_out = watcher.last_step() && *watcher.last_step() >= steps;
    for (Member& c : controllers) {
      if (c.process->running()) continue;
      c.status = c.process->status();
      if (!(last_state_out && succeeded(*c.status))) {
        failure = "controller '" + c.name + "' ended before the run was done (" +
                  describe_status(*c.status) + ")";
        break;
      }
    }
    if (e.lcm_log && !logger.process->running()) failure = "lcm-logger ended during the run";
    if (interrupt.raised()) failure = "interrupted";
    const double wall = seconds_since(began);
    if (wall > e.timeout) failure = format("timeout: %.0f s of wall-clock time", e.timeout);
    if (settings.progress && wall - last_progress >= 1.0) {
      last_progress = wall;
      std::printf("  step %lld of %ld (%.1f steps/s)\n",
                  static_cast<long long>(watcher.last_step().value_or(0)), steps,
                  watcher.steps_per_second());
      std::fflush(stdout);
    }
  }

  // Stop: the server first (its run file closes cleanly on SIGTERM), then the controllers, which
  // end by themselves after the last state, then the logger once the last messages are in.
  stop(server, failure.empty() ? 10.0 : 0.0, SIGTERM, "SIGTERM");
  for (Member& c : controllers) stop(c, 2.0, SIGTERM, "SIGTERM");
  if (e.lcm_log) {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    stop(logger, 0.0, SIGINT, "SIGINT");
  }
  const double wall = seconds_since(began);
  if (failure.empty() && server.status && !succeeded(*server.status)) {
    failure = "sim_server ended with " + describe_status(*server.status) + " (see sim_server.err)";
  }
  for (const Member& c : controllers) {
    if (failure.empty() && c.status && !succeeded(*c.status) && c.stopped_by.empty()) {
      failure = "controller '" + c.name + "' ended with " + describe_status(*c.status);
    }
  }

  std::ostringstream s;
  s << "experiment " << e.name << " (" << e.file.string() << ")\n"
    << "run folder " << folder.string() << "\n"
    << "scene " << e.scene.string() << format(", dt %g ms, %g s", 1e3 * dt, e.duration) << " = "
    << steps << " steps, " << e.server_mode << " mode, bus " << url << ", prefix " << e.prefix
    << "\n\nprocesses (command lines; output in <name>.out and <name>.err):\n";
  std::vector<const Member*> all{&server};
  for (const Member& c : controllers) all.push_back(&c);
  if (e.lcm_log) all.push_back(&logger);
  for (const Member* m : all) {
    s << "  " << m->name << ": "
      << (!m->process ? std::string("not started")
          : m->status ? describe_status(*m->status)
                      : std::string("still running"))
      << (m->stopped_by.empty() ? "" : ", stopped by the runner with " + m->stopped_by) << "\n"
      << "    " << quote(m->argv) << "\n";
  }
  s << format("wall time %.2f s", wall) << "\n";

  std::string figures_error;
  try {
    const RunFigures f = read_run_figures(run_file);
    s << "\nrun file run.h5: status '" << f.status << "', " << f.steps << " steps, "
      << format("%.4g s simulated, physics %.2f s wall (real-time factor %.3g)", f.simulated,
                f.physics_wall, f.physics_wall > 0 ? f.simulated / f.physics_wall : 0.0)
      << ", " << f.newton_iterations << " Newton iterations, " << f.step_cuts << " step cuts\n";
    if (watcher.steps_per_second() > 0.0) {
      s << format(
          "closed loop: %.1f steps/s (%.3g simulated s per wall s), from the states seen "
          "on the bus\n",
          watcher.steps_per_second(), watcher.steps_per_second() * dt);
    }
    if (!f.landmarks.empty()) {
      s << "landmark displacement from the first frame [mm]:      dx       dy       dz   peak "
           "|d| at t [s]\n";
      for (const LandmarkMotion& m : f.landmarks) {
        char line[160];
        std::snprintf(line, sizeof line, "  %-20s %+8.3f %+8.3f %+8.3f %8.3f  %6.3f\n",
                      m.name.c_str(), m.final_mm[0], m.final_mm[1], m.final_mm[2], m.peak_mm,
                      m.peak_time);
        s << line;
      }
    }
  } catch (const std::exception& ex) {
    figures_error = ex.what();
    s << "\nrun file: " << figures_error << "\n";
  }
  if (e.lcm_log) {
    if (const auto b = read_bus_figures(bus_log, channels.state, channels.activation)) {
      s << "LCM log bus.lcmlog: " << b->states << " states, " << b->activations
        << " activations (replay: lcm-logplayer --lcm-url='" << url << "' bus.lcmlog)\n";
    } else {
      s << "LCM log bus.lcmlog: cannot be read\n";
    }
  }

  if (settings.plots && figures_error.empty()) {
    std::vector<std::string> argv{kSystemPython, kPlotScript, run_file.string(), "--out",
                                  fs::absolute(folder).string()};
    if (!e.plot_times.empty()) {
      argv.push_back("--times");
      for (const double t : e.plot_times) argv.push_back(format("%g", t));
    }
    Member plots{"plots", argv};
    try {
      start(plots, folder, folder);
      stop(plots, 120.0, SIGTERM, "SIGTERM");
      s << "plots: "
        << (succeeded(*plots.status)
                ? "written"
                : "FAILED (" + describe_status(*plots.status) + ", see plots.err)")
        << "\n";
      if (!succeeded(*plots.status) && failure.empty()) failure = "plots failed";
    } catch (const std::exception& ex) {
      s << "plots: " << ex.what() << "\n";
      if (failure.empty()) failure = ex.what();
    }
  }

  if (failure.empty() && !figures_error.empty()) failure = "the run file cannot be read";
  s << "\nresult: " << (failure.empty() ? "completed" : "FAILED: " + failure) << "\n";
  outcome.ok = failure.empty();
  const bool unconverged =
      watcher.any_unconverged() || (server.status && WIFEXITED(*server.status) &&
                                    WEXITSTATUS(*server.status) == common::kExitNotConverged);
  outcome.exit_code = outcome.ok           ? common::kExitOk
                      : interrupt.raised() ? common::kExitInterrupted
                      : unconverged        ? common::kExitNotConverged
                                           : common::kExitError;
  outcome.summary = s.str();
  std::ofstream(folder / "summary.txt") << outcome.summary;
  return outcome;
}

}  // namespace tongue::runner
