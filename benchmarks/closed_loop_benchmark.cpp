// The closed loop's pace and where its time goes: sim_server in lock-step with a controller, as
// separate processes on a loopback udpm bus of its own, the way the experiment runner runs them:
//   ai, ku      scenes/tongue_ep.yaml + ep_controller --plan controllers/plans/{ai,ku}.yaml, 0.5 s
//   sg3n_relax  scenes/tongue_sg_3n_relax.yaml + sequence_player
//               --schedule controllers/sequences/sg_3n_relax.yaml, 0.32 s
// each with the scene's solver threads set to 1 and to 2 (a copy of the scene with
// `solver: {threads: N}`). Per run: the steps, simulated s, wall s of the run (sim_server's start
// to its end, settling included), the closed-loop real-time factor (simulated s over the server's
// span from its first step's start to its last one's end, timing_span_s; and the same from the
// first and the last driven state this program sees on the bus), the server's own per-step
// figures from the run file's timing attributes (physics, run file, state message, loop), and the
// bus round trip: the span's time outside the server's steps per wait between two steps (the
// state's way to the controller, its answer, and the activation's way back). Where the scenario
// has a reference run (made by scripts/reference_runs.sh: /ai/ and SG 3 N + relaxation at
// dt 0.1 ms), the RMS nodal error against it [mm], over the frames whose times both runs have,
// as scripts/compare_runs.py computes it. The rows also go to a CSV (default
// logs/closed_loop.csv), which rtf_error_benchmark's diagram draws beside its own settings.
// Last, the bus's own floor under the lock-step overhead: the round trip of a state-sized
// datagram (and of a small one) and a small answer between two processes, with no simulation at
// all.
//
// Usage: closed_loop_benchmark [--runs K] [--csv FILE]   (default 3: medians of K runs per row)
// Uses ports 7795-7799. Build in Release; with K = 3 it takes about 30 s.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <lcm/lcm.h>
#include <yaml-cpp/yaml.h>

#include "bus/channels.hpp"
#include "median.hpp"
#include "run_figures.hpp"
#include "run_file/run_file_reader.hpp"
#include "run_member.hpp"
#include "scene/scene_reader.hpp"
#include "state_watcher.hpp"

#if !defined(SIM_SERVER_PATH) || !defined(EP_CONTROLLER_PATH) || !defined(SEQUENCE_PLAYER_PATH) || \
    !defined(TONGUE_SOURCE_DIR)
#error "the programs' paths and TONGUE_SOURCE_DIR must be defined"
#endif

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using tongue::runner::Member;

constexpr int kFirstPort = 7795;
constexpr int kPorts = 5;
constexpr double kRunTimeout = 600.0;  // s of wall time a run may take
const char* const kPrefix = "TONGUE_";

struct Scenario {
  const char* name;
  const char* scene;                    // relative to the source tree
  double duration;                      // s
  std::vector<std::string> controller;  // the program and its own arguments
  const char* reference;                // its reference run, relative to the source tree; or null
};

std::vector<Scenario> scenarios() {
  const std::string src = TONGUE_SOURCE_DIR;
  return {
      {"ai",
       "scenes/tongue_ep.yaml",
       0.5,
       {EP_CONTROLLER_PATH, "--plan", src + "/controllers/plans/ai.yaml"},
       "logs/reference/ai_reference-latest/run.h5"},
      {"ku",
       "scenes/tongue_ep.yaml",
       0.5,
       {EP_CONTROLLER_PATH, "--plan", src + "/controllers/plans/ku.yaml"},
       nullptr},
      {"sg3n_relax",
       "scenes/tongue_sg_3n_relax.yaml",
       0.32,
       {SEQUENCE_PLAYER_PATH, "--schedule", src + "/controllers/sequences/sg_3n_relax.yaml"},
       "logs/reference/tongue_sg_3n_relax_reference.h5"},
  };
}

// What one run measured; times per step in ms.
struct Figures {
  double steps = 0, simulated = 0, run_wall = 0, rtf = 0, rtf_bus = 0;
  double physics = 0, run_file = 0, state_message = 0, loop = 0, server = 0, wall_step = 0,
         round_trip = 0;
  // The physics' solver per step: iterations, factorizations, and its time [ms] in assembly
  // (residuals and tangents), factorization and solves.
  double iterations = 0, factorizations = 0, assembly = 0, factorization = 0, solve = 0;
  double rms_mm = std::numeric_limits<double>::quiet_NaN();  // against the reference; NaN: none
};

// A reference run's times [s] and positions [m], frame after frame.
struct Reference {
  std::vector<double> time, positions;
  std::size_t frame = 0;  // doubles per frame
};

// The scenario's reference run, when scripts/reference_runs.sh has made it.
std::optional<Reference> load_reference(const Scenario& s) {
  if (!s.reference) return std::nullopt;
  const fs::path path = fs::path(TONGUE_SOURCE_DIR) / s.reference;
  if (!fs::exists(path)) return std::nullopt;
  const tongue::run_file::RunFileReader h5(path.string());
  Reference r{h5.doubles("/time"), h5.doubles("/positions"), 0};
  r.frame = r.time.empty() ? 0 : r.positions.size() / r.time.size();
  return r;
}

// RMS distance [mm] over the nodes and the frames whose times both runs have (frame times are
// sums of dt and carry round-off: equal within 1e-9 s), as scripts/compare_runs.py computes it.
double rms_error_mm(const tongue::run_file::RunFileReader& run, const Reference& ref) {
  const std::vector<double> time = run.doubles("/time"), positions = run.doubles("/positions");
  if (time.empty() || positions.size() != time.size() * ref.frame)
    throw std::runtime_error("the run and its reference are not runs of the same mesh");
  double squares = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < time.size(); ++i) {
    const auto j = std::lower_bound(ref.time.begin(), ref.time.end(), time[i] - 1e-9);
    if (j == ref.time.end() || std::abs(*j - time[i]) > 1e-9) continue;
    const double* a = &positions[i * ref.frame];
    const double* b = &ref.positions[static_cast<std::size_t>(j - ref.time.begin()) * ref.frame];
    for (std::size_t k = 0; k < ref.frame; ++k) squares += (a[k] - b[k]) * (a[k] - b[k]);
    count += ref.frame / 3;
  }
  if (count == 0) throw std::runtime_error("the run and its reference have no time in common");
  return 1e3 * std::sqrt(squares / static_cast<double>(count));
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The scene with its solver's threads set to N (the rest of its solver section kept).
void write_scene_copy(const fs::path& from, int threads, const fs::path& to) {
  YAML::Node scene = YAML::LoadFile(from.string());
  scene["solver"]["threads"] = threads;
  std::ofstream(to) << YAML::Dump(scene) << "\n";
}

double timing_attribute(const tongue::run_file::RunFileReader& h5, const std::string& name) {
  return std::stod(h5.string_attribute("/", name));
}

std::string failure_text(const Member& m, const fs::path& folder) {
  return m.name + " ended with " + tongue::runner::describe_status(m.status.value_or(-1)) +
         " (see " + (folder / (m.name + ".err")).string() + ")";
}

// One run in folder on the given port; throws std::runtime_error when it fails.
Figures run_once(const Scenario& s, int threads, int port, const fs::path& folder,
                 const std::optional<Reference>& reference) {
  fs::create_directories(folder);
  const fs::path scene = folder / "scene.yaml";
  write_scene_copy(fs::path(TONGUE_SOURCE_DIR) / s.scene, threads, scene);
  const std::string url = tongue::bus::default_lcm_url_on_port(port);
  const tongue::bus::Channels channels(kPrefix);
  const double dt = tongue::scene::read_scene(scene.string()).analysis.dt;  // s
  const long steps = std::lround(s.duration / dt);
  const fs::path run_file = folder / "run.h5";

  Member server{"sim_server",
                {SIM_SERVER_PATH, scene.string(), "--lcm-url", url, "--prefix", kPrefix, "--mode",
                 "lockstep", "--output", run_file.string(), "--max-steps", std::to_string(steps)}};
  Member controller{"controller", s.controller};
  for (const std::string& a :
       {std::string("--lcm-url"), url, std::string("--prefix"), std::string(kPrefix),
        std::string("--max-steps"), std::to_string(steps), std::string("--mode"),
        std::string("lockstep")}) {
    controller.argv.push_back(a);
  }

  // Watching before anything starts, so that no state is missed.
  tongue::runner::StateWatcher watcher(url, channels.state);
  const Clock::time_point began = Clock::now();
  tongue::runner::start(server, folder, folder);
  // The controller starts once state 0 is out, as the runner starts it.
  while (!watcher.last_step() && server.process->running() && seconds_since(began) < kRunTimeout)
    watcher.poll(50);
  if (watcher.last_step()) tongue::runner::start(controller, folder, folder);
  while (server.process->running() && seconds_since(began) < kRunTimeout) watcher.poll(50);
  tongue::runner::stop(server, 0.0, SIGTERM, "SIGTERM");
  const double run_wall = seconds_since(began);
  tongue::runner::stop(controller, 5.0, SIGTERM, "SIGTERM");

  if (!tongue::runner::succeeded(*server.status))
    throw std::runtime_error(failure_text(server, folder));
  if (!controller.process) throw std::runtime_error("sim_server sent no state 0");
  if (!tongue::runner::succeeded(*controller.status))
    throw std::runtime_error(failure_text(controller, folder));
  if (watcher.steps_per_second() <= 0.0) throw std::runtime_error("too few states on the bus");

  const tongue::runner::RunFigures rf = tongue::runner::read_run_figures(run_file);
  const tongue::run_file::RunFileReader h5(run_file.string());
  Figures f;
  f.steps = rf.steps;
  f.simulated = rf.simulated;
  f.run_wall = run_wall;
  f.rtf_bus = watcher.steps_per_second() * dt;
  f.physics = timing_attribute(h5, "timing_physics_ms");
  f.run_file = timing_attribute(h5, "timing_run_file_ms");
  f.state_message = timing_attribute(h5, "timing_state_message_ms");
  f.loop = timing_attribute(h5, "timing_loop_ms");
  f.server = f.physics + f.run_file + f.state_message + f.loop;
  f.iterations = timing_attribute(h5, "timing_iterations");
  f.factorizations = timing_attribute(h5, "timing_factorizations");
  f.assembly = timing_attribute(h5, "timing_assembly_ms");
  f.factorization = timing_attribute(h5, "timing_factorization_ms");
  f.solve = timing_attribute(h5, "timing_solve_ms");
  // The server's span holds the steps and the N - 1 waits between them; the first wait (for the
  // controller to start) is before it.
  const double span = timing_attribute(h5, "timing_span_s");
  f.rtf = f.simulated / span;
  f.wall_step = 1e3 * span / f.steps;
  f.round_trip = (1e3 * span - f.steps * f.server) / (f.steps - 1);
  if (reference) f.rms_mm = rms_error_mm(h5, *reference);
  return f;
}

// The bus's own floor under the lock-step overhead: the median round trip of a datagram of
// message_bytes (the tongue's state with all nodes is about 24 kB) answered by one of 200 bytes,
// between this program and a child process of it, on a bus of its own; in ms. Measured first,
// before this program has threads (the child is forked).
double bus_floor_ms(const std::string& url, std::size_t message_bytes) {
  constexpr std::size_t kAnswerBytes = 200;
  constexpr int kRounds = 500;
  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("fork failed");
  if (child == 0) {  // the echo: answers every ping until killed
    lcm_t* echo = lcm_create(url.c_str());
    if (!echo) ::_exit(1);
    lcm_subscribe(
        echo, "FLOOR_PING",
        [](const lcm_recv_buf_t*, const char*, void* e) {
          static const std::vector<char> answer(kAnswerBytes, 0);
          lcm_publish(static_cast<lcm_t*>(e), "FLOOR_PONG", answer.data(),
                      static_cast<unsigned>(answer.size()));
        },
        echo);
    for (;;) lcm_handle(echo);
  }
  struct Ping {
    lcm_t* lcm = nullptr;
    bool answered = false;
    pid_t echo;
    ~Ping() {
      if (lcm) lcm_destroy(lcm);
      ::kill(echo, SIGKILL);
      ::waitpid(echo, nullptr, 0);
    }
  } ping{lcm_create(url.c_str()), false, child};
  if (!ping.lcm) throw std::runtime_error("cannot open the bus " + url);
  lcm_subscribe(
      ping.lcm, "FLOOR_PONG",
      [](const lcm_recv_buf_t*, const char*, void* p) { static_cast<Ping*>(p)->answered = true; },
      &ping);
  const std::vector<char> message(message_bytes, 1);
  std::vector<double> times;
  for (int k = 0; k < kRounds + 20; ++k) {  // the first 20 while the echo starts: not counted
    const Clock::time_point start = Clock::now();
    ping.answered = false;
    lcm_publish(ping.lcm, "FLOOR_PING", message.data(), static_cast<unsigned>(message.size()));
    while (!ping.answered && seconds_since(start) < 1.0) lcm_handle_timeout(ping.lcm, 100);
    if (ping.answered && k >= 20) times.push_back(1e3 * seconds_since(start));
  }
  if (times.size() < kRounds / 2) throw std::runtime_error("the bus lost most of its pings");
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

using tongue::benchmarks::median;

// The median of each figure over the runs.
Figures medians(const std::vector<Figures>& runs) {
  const auto of = [&runs](double Figures::*field) {
    std::vector<double> v;
    for (const Figures& r : runs) v.push_back(r.*field);
    return median(v);
  };
  Figures m;
  for (double Figures::*field :
       {&Figures::steps, &Figures::simulated, &Figures::run_wall, &Figures::rtf, &Figures::rtf_bus,
        &Figures::physics, &Figures::run_file, &Figures::state_message, &Figures::loop,
        &Figures::server, &Figures::wall_step, &Figures::round_trip, &Figures::rms_mm,
        &Figures::iterations, &Figures::factorizations, &Figures::assembly, &Figures::factorization,
        &Figures::solve}) {
    m.*field = of(field);
  }
  return m;
}

struct Options {
  int runs = 3;
  fs::path csv = "logs/closed_loop.csv";
};

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) {
      o.runs = std::atoi(argv[++i]);
    } else if (a == "--csv" && i + 1 < argc) {
      o.csv = argv[++i];
    } else {
      std::fprintf(stderr, "usage: closed_loop_benchmark [--runs K] [--csv FILE]\n");
      std::exit(2);
    }
  }
  if (o.runs < 1) {
    std::fprintf(stderr, "closed_loop_benchmark: --runs must be >= 1\n");
    std::exit(2);
  }
  return o;
}

void print_header(int runs) {
  std::printf(
      "closed loop, lock-step, one controller process; medians of %d run%s; per step in ms\n"
      "%-10s %7s %5s %6s %6s %6s %7s | %7s %7s %7s %7s %7s | %7s %7s | %7s | %5s %5s %6s %6s "
      "%6s\n",
      runs, runs == 1 ? "" : "s", "scenario", "threads", "steps", "sim_s", "wall_s", "RTF",
      "RTF_bus", "physics", "runfile", "state", "loop", "server", "wall", "bus_rt", "RMS_mm", "its",
      "facts", "asm", "fact", "solve");
}

void print_row(const char* name, int threads, const Figures& f) {
  std::printf(
      "%-10s %7d %5.0f %6.3f %6.2f %6.3f %7.3f | %7.2f %7.3f %7.3f %7.3f %7.2f | %7.2f %7.2f | "
      "%7.4f | %5.2f %5.3f %6.3f %6.3f %6.3f\n",
      name, threads, f.steps, f.simulated, f.run_wall, f.rtf, f.rtf_bus, f.physics, f.run_file,
      f.state_message, f.loop, f.server, f.wall_step, f.round_trip, f.rms_mm, f.iterations,
      f.factorizations, f.assembly, f.factorization, f.solve);
  std::fflush(stdout);
}

const char* const kLegend =
    "sim_s: simulated s; wall_s: sim_server's start to its end (settling included);\n"
    "RTF: sim_s / the server's span (first step's start to last step's end, timing_span_s);\n"
    "RTF_bus: the same from the driven states this program saw on the bus;\n"
    "physics (SceneRun::step), runfile (the frame), state (build and publish the message), loop\n"
    "(record the messages) and server (their sum): the run file's timing_*_ms, mean per step;\n"
    "wall: span / steps; bus_rt: (span - steps x server) / (steps - 1), the wait between steps\n"
    "(the state to the controller, its turn, the activation back); RMS_mm: nodal error against\n"
    "the scenario's dt = 0.1 ms reference (nan: none; bash scripts/reference_runs.sh makes them);\n"
    "its, facts: Newton iterations and factorizations per step; asm, fact, solve: the physics'\n"
    "time per step in residual and tangent assembly, factorization and solves (timing_*)\n";

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse_options(argc, argv);
  const fs::path root =
      fs::temp_directory_path() / ("closed_loop_benchmark-" + std::to_string(::getpid()));
  try {
    // The state's size and a small message's: the floor is the other process's waking, which a
    // smaller state does not shorten.
    const std::string floor_url = tongue::bus::default_lcm_url_on_port(kFirstPort);
    const double floor_ms = bus_floor_ms(floor_url, 24000);
    const double small_floor_ms = bus_floor_ms(floor_url, 200);
    if (options.csv.has_parent_path()) fs::create_directories(options.csv.parent_path());
    std::ofstream csv(options.csv);
    if (!csv) throw std::runtime_error("cannot write " + options.csv.string());
    csv << "scenario,threads,rtf,physics_ms,server_ms,rms_mm\n";
    print_header(options.runs);
    int turn = 0;
    for (const Scenario& s : scenarios()) {
      const std::optional<Reference> reference = load_reference(s);
      for (const int threads : {1, 2}) {
        std::vector<Figures> figures;
        for (int k = 0; k < options.runs; ++k, ++turn) {
          // Ports in turn, so that a run never hears a straggler of the one before.
          const fs::path folder = root / (std::string(s.name) + "-t" + std::to_string(threads) +
                                          "-" + std::to_string(k));
          figures.push_back(run_once(s, threads, kFirstPort + turn % kPorts, folder, reference));
        }
        const Figures m = medians(figures);
        print_row(s.name, threads, m);
        csv << s.name << ',' << threads << ',' << m.rtf << ',' << m.physics << ',' << m.server
            << ',' << m.rms_mm << '\n';
      }
    }
    std::printf("%sCSV: %s\n", kLegend, options.csv.c_str());
    std::printf(
        "bus floor: a 24 kB datagram answered by 200 bytes, between two processes on this bus: "
        "median round trip %.3f ms (200 bytes answered by 200: %.3f ms)\n",
        floor_ms, small_floor_ms);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "closed_loop_benchmark: %s (runs kept in %s)\n", e.what(), root.c_str());
    return 1;
  }
  fs::remove_all(root);
  return 0;
}
