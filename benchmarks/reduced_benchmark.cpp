// The reduced model against the full one on runs it was not trained on (docs/reduced.md): the
// paper's experiments as forces (SG 3 N, GGp 4 N, SL 1 N, each rising over 30 ms and held) and
// every muscle at full force, then held-out activation sequences (reduced::training_sequences'
// shapes with levels from another seed: each muscle group stepped and ramped, pairs of groups,
// random mixes), each run by the scene's full model and then by its reduced model (the basis
// given), both through SceneRun from the settled state, each timed on its own. Per run and in all:
// the nodal error of the reduced model against the full one (RMS over nodes and steps, largest),
// each model's stepping time and real-time factor, Newton iterations per step, the error indicator
// at its largest (checked every model.check_every steps, as a scene does), and whether the full
// model's material lost strong ellipticity; in all, also the reduced model's tangent formations
// (and their time) and step cuts.
//
// Usage: reduced_benchmark SCENE BASIS... [--csv FILE] [--seed N] [--pairs N] [--mixes N]
//                          [--duration S]
// With several bases (e.g. of different mode counts and samples), each in turn; one CSV row per
// basis (default logs/reduced.csv), which scripts/plot_rtf_error.py --reduced draws beside the
// full model's settings.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "reduced/training_sequences.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run.hpp"

namespace {

using namespace tongue;
using Clock = std::chrono::steady_clock;

struct Totals {
  double squared_error = 0.0, max_error = 0.0, max_indicator = 0.0;
  double full_s = 0.0, reduced_s = 0.0, simulated_s = 0.0;
  long nodes_steps = 0, steps = 0, full_iterations = 0, reduced_iterations = 0, failures = 0;
  // The reduced model's tangents formed (and their time) and step cuts: where its time goes
  // beyond its iterations.
  long reduced_tangents = 0, reduced_cuts = 0;
  double reduced_tangent_s = 0.0;
  bool lost_ellipticity = false;  // the full model's material, in this run
};

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// A group's total force [N] (both sides) as every muscle of the group at the same level, rising
// over 30 ms and held: the paper's experiments. Level 1 for every muscle: all at full force.
std::vector<reduced::TrainingSequence> experiments(const scene_run::SceneRun& run,
                                                   double duration) {
  const auto& muscles = run.built().muscles->muscles();
  const int n = static_cast<int>(muscles.size());
  std::vector<reduced::TrainingSequence> out;
  const auto held = [&](const std::string& name, const fem::Vector& levels) {
    reduced::TrainingSequence s;
    s.name = name;
    s.times = {0.0, 0.03, duration};
    s.levels = {fem::Vector::Zero(n), levels, levels};
    s.duration = duration;
    out.push_back(s);
  };
  for (const auto& [group, force] :
       std::vector<std::pair<std::string, double>>{{"SG", 3.0}, {"GGp", 4.0}, {"SL", 1.0}}) {
    double total = 0.0;
    for (const auto& m : muscles)
      if (m.name == group || m.name.rfind(group + "_", 0) == 0) total += m.max_force;
    fem::Vector levels = fem::Vector::Zero(n);
    for (int m = 0; m < n; ++m)
      if (muscles[m].name == group || muscles[m].name.rfind(group + "_", 0) == 0)
        levels[m] = std::min(1.0, force / total);
    char name[32];
    std::snprintf(name, sizeof name, "%s %g N", group.c_str(), force);
    held(name, levels);
  }
  held("all at full", fem::Vector::Ones(n));
  return out;
}

// One basis over the held-out sequences: prints a row per run and the totals, returns the row
// for the CSV.
struct BasisRow {
  std::string basis;
  int modes = 0, sampled = 0, runs = 0, stable_runs = 0;
  double rtf = 0.0, full_rtf = 0.0, rms_mm = 0.0, max_mm = 0.0, stable_worst_rms_mm = 0.0;
};

BasisRow evaluate(const scene::Scene& full_scene, const std::string& basis_path,
                  const reduced::TrainingOptions& held_out) {
  scene::Scene reduced_scene = full_scene;
  reduced_scene.model.reduced = basis_path;  // checked every model.check_every steps (10)
  scene_run::SceneRun reduced(reduced_scene, scene::build_scene(reduced_scene));
  if (!reduced.start().converged) throw std::runtime_error("settling failed");
  std::vector<std::string> names;
  for (const auto& m : reduced.built().muscles->muscles()) names.push_back(m.name);
  const double dt = full_scene.analysis.dt;
  const int steps = static_cast<int>(std::ceil(held_out.duration / dt - 1e-9));
  const reduced::ReducedBasis& basis = *reduced.reduced_basis();
  BasisRow row;
  row.basis = basis_path;
  row.modes = static_cast<int>(basis.modes.cols());
  row.sampled = static_cast<int>(basis.sample_elements.size());
  std::printf(
      "%s, basis %s: %d modes, %d of %d elements sampled; held-out seed %u, dt %g ms, "
      "%d steps a run\n",
      full_scene.source.c_str(), basis_path.c_str(), row.modes, row.sampled,
      reduced.built().solid->mesh().num_elements(), held_out.seed, dt * 1e3, steps);
  std::printf("%-16s %8s %8s %9s %9s %7s %7s %12s\n", "run", "RMS[mm]", "max[mm]", "full[ms]",
              "red.[ms]", "it/st", "red.it", "indic[mm]");
  Totals all;
  // Over the runs in which the full model's material stays strongly elliptic (where it can be
  // trusted): the largest run RMS.
  double stable_worst_rms = 0.0;
  // and the reduced model's pace over them [simulated s, wall s].
  double stable_simulated_s = 0.0, stable_reduced_s = 0.0;
  const int nodes = reduced.built().solid->mesh().num_nodes();
  std::vector<reduced::TrainingSequence> sequences = experiments(reduced, held_out.duration);
  for (reduced::TrainingSequence& seq : reduced::training_sequences(names, held_out))
    sequences.push_back(std::move(seq));
  for (const reduced::TrainingSequence& seq : sequences) {
    // A fresh full run for each sequence: a run reports the material's first loss of strong
    // ellipticity once, not again after a restart.
    // Both start with the first step's factor formed under its levels, as sim_batch does.
    const auto levels_at = [&](int step) -> fem::Vector {
      return seq.at(step * dt).cwiseMax(0.0).cwiseMin(1.0);
    };
    scene_run::SceneRun full(full_scene, scene::build_scene(full_scene));
    if (!full.start(levels_at(1)).converged) throw std::runtime_error("settling failed");
    reduced.restart(levels_at(1));
    Totals run;
    // The full run first, then the reduced one, each timed on its own: stepped in turn, each
    // model's step found the other's data in the caches instead of its own (the basis alone is
    // 1.3 MB), which a run of either model does not.
    std::vector<fem::Vector> full_u;
    for (int k = 0; k < steps; ++k) {
      const auto t = Clock::now();
      const scene_run::StepResult f = full.step(dt, levels_at(k + 1));
      run.full_s += seconds_since(t);
      if (f.ellipticity_loss) run.lost_ellipticity = true;
      if (!f.report.converged) break;
      run.full_iterations += f.report.iterations;
      full_u.push_back(full.displacement());
    }
    const int compared = static_cast<int>(full_u.size());
    if (compared < steps) ++run.failures;
    for (int k = 0; k < compared; ++k) {
      const auto t = Clock::now();
      const scene_run::StepResult r = reduced.step(dt, levels_at(k + 1));
      run.reduced_s += seconds_since(t);
      if (!r.report.converged) {
        ++run.failures;
        break;
      }
      run.reduced_iterations += r.report.iterations;
      run.reduced_tangents += r.report.factorizations;
      run.reduced_tangent_s += r.report.factorization_seconds;
      run.reduced_cuts += r.report.cuts;
      const fem::Vector d = reduced.displacement() - full_u[k];
      for (int a = 0; a < nodes; ++a) {
        const double e2 = d.segment<3>(3 * a).squaredNorm();
        run.squared_error += e2;
        run.max_error = std::max(run.max_error, std::sqrt(e2));
      }
      run.nodes_steps += nodes;
      ++run.steps;
      run.simulated_s += dt;
      if (r.reduced_check)
        run.max_indicator = std::max(run.max_indicator, r.reduced_check->correction);
    }
    if (full.finish_checks().ellipticity_loss) run.lost_ellipticity = true;
    if (const auto last = reduced.finish_checks().reduced_check)
      run.max_indicator = std::max(run.max_indicator, last->correction);
    const double rms = std::sqrt(run.squared_error / std::max(1L, run.nodes_steps));
    std::printf("%-16s %8.3f %8.3f %9.1f %9.1f %7.2f %7.2f %12.3f%s%s\n", seq.name.c_str(),
                1e3 * rms, 1e3 * run.max_error, 1e3 * run.full_s, 1e3 * run.reduced_s,
                double(run.full_iterations) / std::max(1L, run.steps),
                double(run.reduced_iterations) / std::max(1L, run.steps), 1e3 * run.max_indicator,
                run.failures ? "  (a step failed)" : "",
                run.lost_ellipticity ? "  (full model: material not elliptic)" : "");
    all.squared_error += run.squared_error;
    all.max_error = std::max(all.max_error, run.max_error);
    all.max_indicator = std::max(all.max_indicator, run.max_indicator);
    all.full_s += run.full_s;
    all.reduced_s += run.reduced_s;
    all.simulated_s += run.simulated_s;
    all.nodes_steps += run.nodes_steps;
    all.steps += run.steps;
    all.full_iterations += run.full_iterations;
    all.reduced_iterations += run.reduced_iterations;
    all.reduced_tangents += run.reduced_tangents;
    all.reduced_tangent_s += run.reduced_tangent_s;
    all.reduced_cuts += run.reduced_cuts;
    all.failures += run.failures;
    if (!run.lost_ellipticity) {
      ++row.stable_runs;
      stable_worst_rms = std::max(stable_worst_rms, rms);
      stable_simulated_s += run.simulated_s;
      stable_reduced_s += run.reduced_s;
    }
  }
  row.runs = static_cast<int>(sequences.size());
  row.rtf = all.simulated_s / all.reduced_s;
  row.full_rtf = all.simulated_s / all.full_s;
  row.rms_mm = 1e3 * std::sqrt(all.squared_error / std::max(1L, all.nodes_steps));
  row.max_mm = 1e3 * all.max_error;
  row.stable_worst_rms_mm = 1e3 * stable_worst_rms;
  std::printf(
      "all: RMS %.3f mm, max %.3f mm; full model RTF %.2f (%.2f it/step), reduced RTF %.2f "
      "(%.2f it/step; %ld tangents formed, %.3f s; %ld cuts), %ld failed runs; largest "
      "indicator %.3f mm\n",
      row.rms_mm, row.max_mm, row.full_rtf, double(all.full_iterations) / std::max(1L, all.steps),
      row.rtf, double(all.reduced_iterations) / std::max(1L, all.steps), all.reduced_tangents,
      all.reduced_tangent_s, all.reduced_cuts, all.failures, 1e3 * all.max_indicator);
  std::printf(
      "runs in which the full model's material stays strongly elliptic: %d of %d, the "
      "worst of them %.3f mm RMS; reduced RTF over them %.2f\n\n",
      row.stable_runs, row.runs, row.stable_worst_rms_mm,
      stable_simulated_s / std::max(1e-12, stable_reduced_s));
  return row;
}

int run(int argc, char** argv) {
  reduced::TrainingOptions held_out;
  held_out.seed = 1001;  // the training's default is 1: other levels, other mixes
  held_out.pairs = 4;
  held_out.mixes = 6;
  std::string csv = "logs/reduced.csv";
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--", 0) != 0) {
      positional.push_back(a);
      continue;
    }
    if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
    const std::string v = argv[++i];
    if (a == "--csv")
      csv = v;
    else if (a == "--seed")
      held_out.seed = static_cast<std::uint32_t>(std::stoul(v));
    else if (a == "--pairs")
      held_out.pairs = std::stoi(v);
    else if (a == "--mixes")
      held_out.mixes = std::stoi(v);
    else if (a == "--duration")
      held_out.duration = std::stod(v);
    else
      throw std::invalid_argument("unknown option " + a);
  }
  if (positional.size() < 2) {
    std::fprintf(stderr,
                 "usage: reduced_benchmark SCENE BASIS... [--csv FILE] [--seed N] [--pairs N] "
                 "[--mixes N] [--duration S]\n");
    return 1;
  }
  const scene::Scene full_scene = scene::read_scene(positional[0]);
  std::vector<BasisRow> rows;
  for (std::size_t b = 1; b < positional.size(); ++b)
    rows.push_back(evaluate(full_scene, positional[b], held_out));
  std::filesystem::create_directories(std::filesystem::absolute(csv).parent_path());
  std::ofstream out(csv);
  out << "basis,modes,sampled,rtf,full_rtf,rms_mm,max_mm,runs,stable_runs,stable_worst_rms_mm\n";
  for (const BasisRow& r : rows)
    out << r.basis << ',' << r.modes << ',' << r.sampled << ',' << r.rtf << ',' << r.full_rtf << ','
        << r.rms_mm << ',' << r.max_mm << ',' << r.runs << ',' << r.stable_runs << ','
        << r.stable_worst_rms_mm << '\n';
  if (!out) throw std::runtime_error("cannot write " + csv);
  std::printf("CSV: %s (scripts/plot_rtf_error.py --reduced draws it)\n", csv.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "reduced_benchmark: error: %s\n", e.what());
    return 1;
  }
}
