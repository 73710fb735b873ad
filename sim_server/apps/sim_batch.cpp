// sim_batch SCENE.yaml [--output FILE] [--quiet]
//
// Runs a scene to the end without a message bus and logs it to an HDF5 run file: a static
// analysis (the rest frame and each load increment) or a dynamic one (optionally settled under its
// loads first, then steps of dt until the duration, every k-th step logged). Muscles follow the
// scene's activation schedule: a dynamic step to t_{n+1} uses the levels at t_{n+1} (the initial
// state, settling included, has every muscle off), a static solve those at t = 0.
//
// Exit status: 0 done; 1 bad command line, scene error or I/O error; 2 a step or load increment
// failed to converge even after cuts (the frames written so far are kept); 130 interrupted.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <optional>
#include <string>

#include "fem/assembly/ellipticity_monitor.hpp"
#include "fem/integrator/newmark_integrator.hpp"
#include "fem/integrator/static_solver.hpp"
#include "logging/position_log.hpp"
#include "logging/scene_run_file.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "tongue/default_tongue.hpp"

namespace tongue::apps {
namespace {

constexpr int kExitOk = 0;
constexpr int kExitError = 1;
constexpr int kExitNotConverged = 2;
constexpr int kExitInterrupted = 130;

volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int) {
  g_interrupted = 1;
}

struct Options {
  std::string scene_path;
  std::optional<std::string> output;
  bool quiet = false;
};

void print_usage(std::FILE* to) {
  std::fprintf(to,
               "usage: sim_batch SCENE.yaml [--output FILE] [--quiet]\n"
               "  --output FILE  run file to write (overrides the scene's output.file)\n"
               "  --quiet        no per-step lines, only the summary\n");
}

// Returns nullopt (after printing why) on a bad command line.
std::optional<Options> parse_arguments(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      print_usage(stdout);
      std::exit(kExitOk);
    } else if (arg == "--quiet" || arg == "-q") {
      options.quiet = true;
    } else if (arg == "--output" || arg == "-o") {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "sim_batch: %s needs a file name\n", arg.c_str());
        return std::nullopt;
      }
      options.output = argv[++i];
    } else if (arg.rfind("--output=", 0) == 0) {
      options.output = arg.substr(9);
    } else if (!arg.empty() && arg[0] == '-') {
      std::fprintf(stderr, "sim_batch: unknown option '%s'\n", arg.c_str());
      return std::nullopt;
    } else if (options.scene_path.empty()) {
      options.scene_path = arg;
    } else {
      std::fprintf(stderr, "sim_batch: more than one scene given ('%s')\n", arg.c_str());
      return std::nullopt;
    }
  }
  if (options.scene_path.empty()) {
    std::fprintf(stderr, "sim_batch: no scene given\n");
    return std::nullopt;
  }
  return options;
}

// Totals over the steps since the last logged frame, and over the whole run.
struct Tally {
  int steps = 0, iterations = 0, cuts = 0, factorizations = 0, residuals = 0;
  double assembly = 0.0, factorization = 0.0, solve = 0.0;  // s
  double wall = 0.0;                                        // s
  double residual = 0.0;

  void add(const fem::StepReport& r) {
    ++steps;
    iterations += r.iterations;
    cuts += r.cuts;
    factorizations += r.factorizations;
    residuals += r.residual_evaluations;
    assembly += r.assembly_seconds;
    factorization += r.factorization_seconds;
    solve += r.solve_seconds;
    wall += r.wall_seconds;
    residual = r.final_residual;
  }
  logging::SolverFigures figures() const { return {iterations, residual, wall, cuts}; }
};

class BatchRun {
 public:
  BatchRun(const scene::Scene& scene, scene::BuiltScene built, const std::string& output,
           bool quiet)
      : scene_(scene), built_(std::move(built)), quiet_(quiet) {
    const fem::SolidModel& solid = *built_.solid;
    if (!output.empty()) log_ = logging::open_scene_run_file(output, scene_, built_);
    std::printf(
        "%s: %d nodes, %d hex8, %d free dofs, mass %.4g kg, volume %.4g cm^3, %d muscles, %s "
        "analysis\n",
        scene_.source.c_str(), solid.mesh().num_nodes(), solid.mesh().num_elements(),
        solid.dofs().num_free(), solid.total_mass(), solid.reference_volume() * 1e6,
        built_.muscles ? built_.muscles->num_muscles() : 0, is_dynamic() ? "dynamic" : "static");
    if (log_) {
      std::printf("run file: %s\n", output.c_str());
    } else {
      std::printf("no run file (give --output or output.file)\n");
    }
  }

  int run() {
    const auto start = std::chrono::steady_clock::now();
    int status = kExitError;
    try {
      status = is_dynamic() ? run_dynamic() : run_static();
    } catch (const std::exception& e) {
      // E.g. an inverted element in the initial state, or a run file that cannot be written:
      // mark the file, which keeps the frames written so far.
      failure_ = e.what();
      std::fprintf(stderr, "sim_batch: error: %s\n", e.what());
    }
    wall_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary(status);
    if (log_) {
      log_->set_attribute("status", status == kExitOk            ? "completed"
                                    : status == kExitInterrupted ? "interrupted"
                                                                 : "failed: " + failure_);
      log_->flush();
    }
    return status;
  }

 private:
  bool is_dynamic() const { return scene_.analysis.type == scene::AnalysisType::dynamic; }

  // Static equilibrium by load stepping: the rest frame, then one frame per load increment.
  int run_static() {
    fem::Vector u = fem::Vector::Zero(built_.solid->num_dofs());
    set_activations(0.0);
    initial_u_ = u;
    write_frame(0.0, u, nullptr, {});
    Tally tally;
    header("incr", "lambda [1]");
    // One frame per accepted load increment, written as it is reached: a failure later keeps
    // everything up to the last accepted increment.
    const fem::StaticReport report =
        fem::solve_static(*built_.system, u, built_.static_settings,
                          [&](const fem::StepReport& inc, const fem::Vector& reached) {
                            Tally one;
                            one.add(inc);
                            tally.add(inc);
                            step_line(tally.steps, inc.time, inc);
                            track(reached);
                            check_material(inc.time, reached);
                            write_frame(inc.time, reached, nullptr, one.figures());
                          });
    total_.steps += tally.steps;
    total_.iterations += tally.iterations;
    total_.cuts += tally.cuts;
    if (!report.converged) {
      failure_ = report.message;
      std::fprintf(stderr, "sim_batch: static solution failed: %s\n", report.message.c_str());
      return kExitNotConverged;
    }
    return kExitOk;
  }

  int run_dynamic() {
    const scene::AnalysisSpec& a = scene_.analysis;
    const int n = built_.solid->num_dofs();
    fem::Vector u = fem::Vector::Zero(n);
    Tally settle;
    if (a.settle) {
      // Rest under gravity and loads is the state before any muscle acts (all levels are 0
      // until the first step sets them).
      const fem::StaticReport report = fem::solve_static(*built_.system, u, built_.static_settings);
      for (const fem::StepReport& inc : report.increments) settle.add(inc);
      if (!quiet_)
        std::printf(
            "settle: %d increments, %d iterations, %d cuts, residual %.3e N, wall %.1f ms\n",
            settle.steps, settle.iterations, settle.cuts, settle.residual, settle.wall * 1e3);
      total_.iterations += settle.iterations;
      total_.cuts += settle.cuts;
      if (!report.converged) {
        failure_ = "settling: " + report.message;
        std::fprintf(stderr, "sim_batch: settling failed: %s\n", report.message.c_str());
        return kExitNotConverged;
      }
    }
    // Damping's K0 is the tangent where the integrator is initialized: the settled state if
    // the scene settles, else the rest state. The initial acceleration is taken with every
    // muscle off, and the muscles act from the first step on (levels at its end time): a step
    // of force in a_0 would make the average-acceleration scheme's velocities flip sign from
    // step to step in the stiff modes the fibre end forces excite.
    if (built_.muscles)
      built_.muscles->set_activations(fem::Vector::Zero(built_.muscles->num_muscles()));
    fem::NewmarkIntegrator integrator(*built_.system, built_.dynamic_settings);
    integrator.initialize(u, fem::Vector::Zero(n), 0.0);
    initial_u_ = integrator.displacement();
    track(integrator.displacement());
    write_frame(0.0, integrator.displacement(), &integrator.velocity(), settle.figures());

    const int count = scene::time_step_count(a);
    const int every = scene_.output.every;
    header("step", "t [s]");
    Tally since_frame;
    for (int s = 0; s < count; ++s) {
      if (g_interrupted) {
        std::fprintf(stderr, "sim_batch: interrupted at t = %.6g s\n", integrator.time());
        return kExitInterrupted;
      }
      const double t0 = integrator.time();
      const double dt = scene::time_step_length(a, s);
      set_activations(t0 + dt);
      const fem::StepReport r = integrator.step(dt);
      since_frame.add(r);
      ++total_.steps;
      total_.iterations += r.iterations;
      total_.cuts += r.cuts;
      stepping_.add(r);
      step_line(s + 1, r.time, r);
      if (!r.converged) {
        failure_ = r.message;
        std::fprintf(stderr,
                     "sim_batch: step %d (from t = %.6g s, dt = %.6g s) failed to converge: %s\n",
                     s + 1, t0, r.dt, r.message.c_str());
        return kExitNotConverged;
      }
      simulated_ = integrator.time();
      track(integrator.displacement());
      check_material(integrator.time(), integrator.displacement());
      if ((s + 1) % every == 0 || s + 1 == count) {
        write_frame(integrator.time(), integrator.displacement(), &integrator.velocity(),
                    since_frame.figures());
        since_frame = Tally{};
      }
    }
    return kExitOk;
  }

  // Says once, on stderr and in the run file, when the material first loses strong ellipticity.
  void check_material(double t, const fem::Vector& u) {
    const auto loss = monitor_.first_loss(u);
    if (!loss) return;
    const std::string text = fem::describe(*loss, built_.solid->material());
    std::fprintf(stderr, "sim_batch: warning: at t = %.6g s %s\n", t, text.c_str());
    if (log_) log_->set_attribute("material_warning", "t = " + std::to_string(t) + " s: " + text);
  }

  void set_activations(double t) {
    if (built_.muscles) built_.muscles->set_activations(built_.activations.levels_at(t));
  }

  // v: nodal velocities, null for a static frame (at rest).
  void write_frame(double time, const fem::Vector& u, const fem::Vector* v,
                   const logging::SolverFigures& figures) {
    if (!log_) return;
    const logging::MuscleFrame muscles = logging::scene_muscle_frame(built_, u, v);
    log_->append(time, built_.solid->rest_positions() + u, figures, muscles);
  }

  // Largest nodal displacement and volume change seen so far.
  void track(const fem::Vector& u) {
    last_u_ = u;
    final_displacement_ = 0.0;
    for (int node = 0; node < u.size() / 3; ++node)
      final_displacement_ = std::max(final_displacement_, u.segment<3>(3 * node).norm());
    max_displacement_ = std::max(max_displacement_, final_displacement_);
    const fem::SolidModel& solid = *built_.solid;
    volume_change_ = solid.current_volume(u) / solid.reference_volume() - 1.0;
    max_volume_change_ = std::max(max_volume_change_, std::abs(volume_change_));
  }

  void header(const char* step, const char* time) const {
    if (quiet_) return;
    std::printf("%6s %12s %5s %13s %10s %5s\n", step, time, "iter", "residual [N]", "wall [ms]",
                "cuts");
  }

  void step_line(int step, double time, const fem::StepReport& r) const {
    if (quiet_) return;
    std::printf("%6d %12.6f %5d %13.3e %10.2f %5d%s\n", step, time, r.iterations, r.final_residual,
                r.wall_seconds * 1e3, r.cuts, r.converged ? "" : "  NOT CONVERGED");
    if (r.cuts > 0 && r.converged) std::printf("       cut: %s\n", r.message.c_str());
  }

  void summary(int status) const {
    std::printf("summary: %s, %d %s, %d cuts, %d Newton iterations, wall %.3f s",
                status == kExitOk            ? "completed"
                : status == kExitInterrupted ? "interrupted"
                                             : "FAILED",
                total_.steps, is_dynamic() ? "steps" : "increments", total_.cuts, total_.iterations,
                wall_);
    if (is_dynamic()) {
      std::printf(", simulated %.4g s, real-time factor %.3g", simulated_,
                  wall_ > 0.0 ? simulated_ / wall_ : 0.0);
      // The steps alone (no settling, set-up or run file): what a running server sustains.
      std::printf(
          "\n         stepping: wall %.3f s, real-time factor %.3g; %d residuals (assembly "
          "%.3f s), %d factorizations (%.3f s), solves %.3f s",
          stepping_.wall, stepping_.wall > 0.0 ? simulated_ / stepping_.wall : 0.0,
          stepping_.residuals, stepping_.assembly, stepping_.factorizations,
          stepping_.factorization, stepping_.solve);
    }
    std::printf(
        "\n         max displacement %.4g mm (last %.4g mm), volume change %+.4f %% "
        "(largest |change| %.4f %%)\n",
        max_displacement_ * 1e3, final_displacement_ * 1e3, volume_change_ * 100.0,
        max_volume_change_ * 100.0);
    landmarks();
    if (log_)
      std::printf("         run file %s: %d frames\n", log_->path().c_str(), log_->frames());
  }

  // Mean displacement of each landmark set the mesh has (the tongue's), from the first frame
  // (the settled state when the scene settles) to the last state reached.
  void landmarks() const {
    if (initial_u_.size() == 0 || last_u_.size() != initial_u_.size()) return;
    const fem::Mesh& mesh = built_.solid->mesh();
    bool first = true;
    for (const std::string& name : model::landmark_names()) {
      const auto it = mesh.node_sets.find(name);
      if (it == mesh.node_sets.end() || it->second.empty()) continue;
      fem::Vec3 d = fem::Vec3::Zero();
      for (int node : it->second)
        d += last_u_.segment<3>(3 * node) - initial_u_.segment<3>(3 * node);
      d /= static_cast<double>(it->second.size());
      if (first)
        std::printf("         landmark displacement since the first frame [mm]: %8s %8s %8s %8s\n",
                    "dx", "dy", "dz", "|d|");
      first = false;
      std::printf("           %-47s %+8.3f %+8.3f %+8.3f %8.3f\n", name.c_str(), d.x() * 1e3,
                  d.y() * 1e3, d.z() * 1e3, d.norm() * 1e3);
    }
  }

  const scene::Scene& scene_;
  scene::BuiltScene built_;
  bool quiet_;
  std::unique_ptr<logging::PositionLog> log_;
  Tally total_;
  Tally stepping_;  // the dynamic steps alone
  std::string failure_;
  fem::EllipticityMonitor monitor_{*built_.solid};
  double wall_ = 0.0, simulated_ = 0.0;
  double max_displacement_ = 0.0, final_displacement_ = 0.0;  // m
  double volume_change_ = 0.0, max_volume_change_ = 0.0;      // relative
  fem::Vector initial_u_, last_u_;                            // m, first frame and last state
};

int run(int argc, char** argv) {
  const std::optional<Options> options = parse_arguments(argc, argv);
  if (!options) {
    print_usage(stderr);
    return kExitError;
  }
  try {
    const scene::Scene scene = scene::read_scene(options->scene_path);
    scene::BuiltScene built = scene::build_scene(scene);
    const std::string output = options->output ? *options->output : scene.output.file;
    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
    BatchRun batch(scene, std::move(built), output, options->quiet);
    return batch.run();
  } catch (const scene::SceneError& e) {
    std::fprintf(stderr, "sim_batch: scene error: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sim_batch: error: %s\n", e.what());
  }
  return kExitError;
}

}  // namespace
}  // namespace tongue::apps

int main(int argc, char** argv) {
  return tongue::apps::run(argc, argv);
}
