// sim_batch SCENE.yaml [--output FILE] [--quiet]
//
// Runs a scene to the end without a message bus and logs it to an HDF5 run file: a static
// analysis (the rest frame and each load increment) or a dynamic one (optionally settled under its
// loads first, then steps of dt until the duration, every k-th step logged). Muscles follow the
// scene's activation schedule: a dynamic step to t_{n+1} uses the levels at t_{n+1} (the initial
// state, settling included, has every muscle off), a static solve those at t = 0.
//
// Exit status (common/exit_code.hpp): 0 done; 1 bad command line, scene error or I/O error; 2 a
// step or load increment failed to converge even after cuts (the frames written so far are
// kept); 130 interrupted.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <optional>
#include <string>

#include "common/exit_code.hpp"
#include "common/interrupt.hpp"
#include "fem/assembly/ellipticity_monitor.hpp"
#include "fem/integrator/static_solver.hpp"
#include "fem/integrator/step_totals.hpp"
#include "model/default_tongue.hpp"
#include "run_file/run_file_queue.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run.hpp"
#include "scene_run/scene_run_file.hpp"

namespace tongue::apps {
namespace {

using common::kExitError;
using common::kExitInterrupted;
using common::kExitNotConverged;
using common::kExitOk;

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
struct Tally : fem::StepTotals {
  run_file::SolverFigures figures() const { return {iterations, residual, wall, cuts}; }
};

class BatchRun {
 public:
  BatchRun(const scene::Scene& scene, scene::BuiltScene built_scene, const std::string& output,
           bool quiet, const common::InterruptHandlers& interrupt)
      : scene_(scene), quiet_(quiet), interrupt_(interrupt) {
    if (is_dynamic()) {
      run_ = std::make_unique<scene_run::SceneRun>(scene_, std::move(built_scene));
    } else {
      built_ = std::move(built_scene);
    }
    const fem::SolidModel& solid = *built().solid;
    if (!output.empty())
      log_ = std::make_unique<run_file::RunFileQueue>(
          scene_run::open_scene_run_file(output, scene_, built()));
    std::printf(
        "%s: %d nodes, %d hex8, %d free dofs, mass %.4g kg, volume %.4g cm^3, %d muscles, %s "
        "analysis\n",
        scene_.source.c_str(), solid.mesh().num_nodes(), solid.mesh().num_elements(),
        solid.dofs().num_free(), solid.total_mass(), solid.reference_volume() * 1e6,
        built().muscles ? built().muscles->num_muscles() : 0, is_dynamic() ? "dynamic" : "static");
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
      const int result = is_dynamic() ? run_dynamic() : run_static();
      // Waits for the queued frames: the summary counts them, and a write error fails the run.
      if (log_) log_->flush();
      status = result;
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
    fem::Vector u = fem::Vector::Zero(built().solid->num_dofs());
    set_activations(0.0);
    initial_u_ = u;
    track(u);
    write_frame(0.0, u, scene_run::scene_muscle_frame(built(), u, nullptr), {});
    Tally tally;
    header("incr", "lambda [1]");
    // One frame per accepted load increment, written as it is reached: a failure later keeps
    // everything up to the last accepted increment.
    const fem::StaticReport report = fem::solve_static(
        *built().system, u, built().static_settings,
        [&](const fem::StepReport& inc, const fem::Vector& reached) {
          Tally one;
          one.add(inc);
          tally.add(inc);
          step_line(tally.steps, inc.time, inc);
          track(reached);
          check_material(inc.time, reached);
          write_frame(inc.time, reached, scene_run::scene_muscle_frame(built(), reached, nullptr),
                      one.figures());
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
    scene_run::SceneRun& run = *run_;
    // The schedule's first levels are known now: the first step's factor is formed with them.
    const fem::StaticReport settled = run.start(levels_at(scene::time_step_length(a, 0)));
    Tally settle;
    if (a.settle) {
      for (const fem::StepReport& inc : settled.increments) settle.add(inc);
      if (!quiet_)
        std::printf(
            "settle: %d increments, %d iterations, %d cuts, residual %.3e N, wall %.1f ms\n",
            settle.steps, settle.iterations, settle.cuts, settle.residual, settle.wall * 1e3);
      total_.iterations += settle.iterations;
      total_.cuts += settle.cuts;
      if (!settled.converged) {
        failure_ = "settling: " + settled.message;
        std::fprintf(stderr, "sim_batch: settling failed: %s\n", settled.message.c_str());
        return kExitNotConverged;
      }
    }
    initial_u_ = run.displacement();
    track(run.displacement());
    write_frame(0.0, run.displacement(), run.muscle_frame(), settle.figures());

    const int count = scene::time_step_count(a);
    const int every = scene_.output.every;
    header("step", "t [s]");
    Tally since_frame;
    for (int s = 0; s < count; ++s) {
      if (interrupt_.raised()) {
        std::fprintf(stderr, "sim_batch: interrupted at t = %.6g s\n", run.time());
        return kExitInterrupted;
      }
      const double t0 = run.time();
      const double dt = scene::time_step_length(a, s);
      const scene_run::StepResult r = run.step(dt, levels_at(t0 + dt));
      since_frame.add(r.report);
      ++total_.steps;
      total_.iterations += r.report.iterations;
      total_.cuts += r.report.cuts;
      stepping_.add(r.report);
      step_line(s + 1, r.report.time, r.report);
      if (r.ellipticity_loss) material_warning(*r.ellipticity_loss);
      if (r.reduced_warning) reduced_warning(*r.reduced_warning);
      if (!r.report.converged) {
        failure_ = r.report.message;
        std::fprintf(stderr,
                     "sim_batch: step %d (from t = %.6g s, dt = %.6g s) failed to converge: %s\n",
                     s + 1, t0, r.report.dt, r.report.message.c_str());
        return kExitNotConverged;
      }
      simulated_ = run.time();
      track(run.displacement());
      if ((s + 1) % every == 0 || s + 1 == count) {
        run_file::SolverFigures figures = since_frame.figures();
        figures.reduced_correction = run.reduced_correction();
        write_frame(run.time(), run.displacement(), r.muscles, figures);
        since_frame = Tally{};
      }
    }
    const scene_run::FinishedChecks last = run.finish_checks();
    if (last.ellipticity_loss) material_warning(*last.ellipticity_loss);
    if (last.reduced_warning) reduced_warning(*last.reduced_warning);
    return kExitOk;
  }

  // The scene's activation levels at time t (none without muscles).
  fem::Vector levels_at(double t) const {
    return built().muscles ? built().activations.levels_at(t) : fem::Vector();
  }

  // A dynamic scene is built into its run; a static one stays here.
  const scene::BuiltScene& built() const { return run_ ? run_->built() : built_; }

  // Says once, on stderr and in the run file, when the material first loses strong ellipticity.
  void reduced_warning(const std::string& text) {
    std::fprintf(stderr, "sim_batch: warning: %s\n", text.c_str());
    if (log_) log_->set_attribute("reduced_model_warning", text);
  }

  void material_warning(const scene_run::EllipticityFinding& found) {
    material_warning(found.time, found.warning);
  }
  void material_warning(double t, const std::string& text) {
    std::fprintf(stderr, "sim_batch: warning: at t = %.6g s %s\n", t, text.c_str());
    if (log_) log_->set_attribute("material_warning", "t = " + std::to_string(t) + " s: " + text);
  }

  // A static run's check of the material at each increment (a dynamic run's is in SceneRun).
  void check_material(double t, const fem::Vector& u) {
    if (!monitor_) monitor_ = std::make_unique<fem::EllipticityMonitor>(*built().solid);
    if (const auto loss = monitor_->first_loss(u))
      material_warning(t, fem::describe(*loss, built().solid->material(), built().numbering));
  }

  void set_activations(double t) {
    if (built().muscles) built().muscles->set_activations(built().activations.levels_at(t));
  }

  // The frame of displacement u, after track(u): its contact is the one track found.
  void write_frame(double time, const fem::Vector& u, const run_file::MuscleFrame& muscles,
                   const run_file::SolverFigures& figures) {
    if (!log_) return;
    log_->append(time, built().solid->rest_positions() + u, figures, muscles,
                 scene_run::scene_contact_frame(built(), last_contact_));
  }

  // Largest nodal displacement, volume change and penetration of an obstacle seen so far.
  void track(const fem::Vector& u) {
    last_u_ = u;
    final_displacement_ = 0.0;
    for (int node = 0; node < u.size() / 3; ++node)
      final_displacement_ = std::max(final_displacement_, u.segment<3>(3 * node).norm());
    max_displacement_ = std::max(max_displacement_, final_displacement_);
    const fem::SolidModel& solid = *built().solid;
    volume_change_ = solid.current_volume(u) / solid.reference_volume() - 1.0;
    max_volume_change_ = std::max(max_volume_change_, std::abs(volume_change_));
    if (built().contact) {
      last_contact_ = built().contact->report(u);
      max_penetration_ = std::max(max_penetration_, last_contact_.max_penetration);
    }
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
    if (r.constraint_unmet)
      std::printf(
          "       contact: deeper than the penetration tolerance, max_augmentations spent\n");
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
    contact();
    if (log_)
      std::printf("         run file %s: %d frames\n", log_->path().c_str(), log_->frames());
  }

  // The deepest penetration of an obstacle over the run and the contact at its end.
  void contact() const {
    if (!built().contact) return;
    const auto& obstacles = built().contact->obstacles();
    std::printf("         contact: max penetration %.4f mm, %d augmented solves; ",
                max_penetration_ * 1e3, stepping_.augmentations);
    if (stepping_.constraints_unmet > 0) {
      std::printf(
          "steps accepted deeper than the penetration tolerance (max_augmentations "
          "spent): %d; ",
          stepping_.constraints_unmet);
    }
    std::printf("at the end %zu nodes in contact, ", last_contact_.contacts.size());
    std::printf("force on each obstacle [N]:\n");
    for (std::size_t o = 0; o < obstacles.size(); ++o) {
      const fem::Vec3 f = o < last_contact_.obstacle_force.size() ? last_contact_.obstacle_force[o]
                                                                  : fem::Vec3::Zero();
      std::printf("           %-48s %+8.4f %+8.4f %+8.4f %8.4f\n", obstacles[o]->name().c_str(),
                  f.x(), f.y(), f.z(), f.norm());
    }
  }

  // Mean displacement of each landmark set the mesh has (the tongue's), from the first frame
  // (the settled state when the scene settles) to the last state reached.
  void landmarks() const {
    if (initial_u_.size() == 0 || last_u_.size() != initial_u_.size()) return;
    const fem::Mesh& mesh = built().solid->mesh();
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
  const common::InterruptHandlers& interrupt_;
  std::unique_ptr<run_file::RunFileQueue> log_;  // written on its own thread
  Tally total_;
  Tally stepping_;  // the dynamic steps alone
  std::string failure_;
  std::unique_ptr<scene_run::SceneRun> run_;          // a dynamic scene's run
  std::unique_ptr<fem::EllipticityMonitor> monitor_;  // a static run's
  double wall_ = 0.0, simulated_ = 0.0;
  double max_displacement_ = 0.0, final_displacement_ = 0.0;  // m
  double volume_change_ = 0.0, max_volume_change_ = 0.0;      // relative
  fem::ContactReport last_contact_;                           // at the last state tracked
  double max_penetration_ = 0.0;                              // m, over the run
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
    const common::InterruptHandlers interrupt;
    BatchRun batch(scene, std::move(built), output, options->quiet, interrupt);
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
