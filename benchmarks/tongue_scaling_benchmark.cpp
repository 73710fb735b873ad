// Cost of the built-in tongue against its element count (docs/speed.md): the parts of one Newton
// iteration and the cost of a dynamic step at refinement 1, 2 (and 3 with --max-refinement 3),
// with the exponent p of a least-squares fit cost ~ elements^p.
//
// Scene: scenes/tongue_sg_3n.yaml with the refinement changed (mooney_rivlin5, mean dilatation,
// gravity, SG 3 N, dt = 4 ms, the scene's default solver settings). Each mesh is settled, then
// --steps dynamic steps of SG 3 N are timed (cost per step, wall), and the parts are timed at the
// settled state: residual alone, residual + tangent, numeric factorization and one solve
// (medians of --reps), and on a line of their own the solid's element pass, the fibre forces,
// one product with M in compressed columns and one in node blocks, and one solve with the
// factor in single precision with its difference from the double one. Also a step at rest (no
// muscle active) for the rest cost.
// Times are the thread's CPU time on 1 thread (robust on a shared machine), wall time otherwise
// or with --wall (to compare 1 and 2 threads on the same clock); the factorization is always wall
// time (CHOLMOD uses threads of its own).
//
// Usage: tongue_scaling_benchmark [--max-refinement N] [--steps N] [--reps N] [--threads N]
//                                 [--wall]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <string>
#include <vector>

#include "fem/assembly/node_block_matrix.hpp"
#include "fem/integrator/newmark_integrator.hpp"
#include "fem/solver/cholmod_solver.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run.hpp"

namespace {

using namespace tongue;
using Clock = std::chrono::steady_clock;

// On one thread the calling thread's CPU time: the work done, unaffected by other processes
// taking the core (this 2-core machine is shared); with more threads the wall time.
bool g_thread_clock = true;

double now_seconds() {
  if (!g_thread_clock)
    return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

template <class F>
double median_seconds(int reps, F&& f) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const double start = now_seconds();
    f();
    t.push_back(now_seconds() - start);
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}

struct Row {
  int refinement = 0, nodes = 0, elements = 0, free_dofs = 0;
  double nnz_L = 0.0;
  double residual = 0.0, residual_active = 0.0, tangent = 0.0, factorization = 0.0,
         solve = 0.0;                         // s
  double step_active = 0.0, step_rest = 0.0;  // s per step
  double iterations_per_step = 0.0, factorizations_per_step = 0.0;
};

Row measure(const scene::Scene& base, int refinement, int steps, int reps, int threads) {
  scene::Scene s = base;
  s.mesh = scene::TongueMeshSpec{refinement};
  s.threads = threads;
  s.output.file.clear();
  scene_run::SceneRun run(s, scene::build_scene(s));
  const scene::BuiltScene& built = run.built();
  const fem::SolidModel& solid = *built.solid;
  Row row;
  row.refinement = refinement;
  row.nodes = solid.mesh().num_nodes();
  row.elements = solid.mesh().num_elements();
  row.free_dofs = solid.dofs().num_free();

  const fem::StaticReport settled = run.start();
  if (!settled.converged) throw std::runtime_error("settling failed: " + settled.message);
  const fem::Vector u = run.displacement();

  // The parts of an iteration at the settled state (the muscles set directly: these time the
  // model's parts, not a run).
  fem::Vector r;
  fem::SymmetricMatrix K(solid.pattern());
  row.residual = median_seconds(reps, [&] { built.system->residual(u, 1.0, r, nullptr); });
  // With SG active: the fibre forces and the stiffened elements' second pass come in.
  built.muscles->set_activations(built.activations.levels_at(s.analysis.dt));
  row.residual_active = median_seconds(reps, [&] { built.system->residual(u, 1.0, r, nullptr); });
  {
    fem::Vector f;
    const double solid_only = median_seconds(reps, [&] { solid.assemble(u, f, nullptr); });
    const fem::SymmetricMatrix M0 = solid.mass_matrix(false);
    const double product = median_seconds(reps, [&] { M0.multiply_add(u.head(row.free_dofs), f); });
    // The same product in node blocks on full vectors, as the time steps do it, with a
    // tangent's pattern of full 3 x 3 blocks (K + M).
    fem::SymmetricMatrix KM = M0;
    solid.assemble(u, f, &KM);
    KM.scale_and_add(1.0, 1e5, M0);
    const fem::NodeBlockMatrix blocks(KM, solid.dofs());
    fem::Vector y = fem::Vector::Zero(u.size());
    const double block_product = median_seconds(reps, [&] { blocks.multiply_add(u, y); });
    std::printf("  refinement %d: one product in node blocks %.3f ms\n", refinement,
                block_product * 1e3);
    const double fibres =
        median_seconds(reps, [&] { built.muscles->add(u, 1.0, f, nullptr); });  // SG active
    std::printf(
        "  refinement %d: solid alone %.3f ms, fibre forces (SG) %.3f ms, one product with M "
        "%.3f ms\n",
        refinement, solid_only * 1e3, fibres * 1e3, product * 1e3);
  }
  built.muscles->set_activations(fem::Vector::Zero(built.muscles->num_muscles()));
  row.tangent = median_seconds(std::max(1, reps / 3), [&] {
    K.set_zero();
    built.system->residual(u, 1.0, r, &K);
  });
  fem::CholmodSolver chol(solid.pattern());
  // K alone may be singular along constrained-free rigid modes: factor K + M, as in dynamics.
  const fem::SymmetricMatrix M = solid.mass_matrix(false);
  K.scale_and_add(1.0, 1e5, M);
  {
    // CHOLMOD runs parts of the factorization on its own OpenMP threads: wall time here, the
    // best of the repetitions (the least disturbed by other processes).
    const bool thread_clock = g_thread_clock;
    g_thread_clock = false;
    row.factorization = 1e300;
    for (int i = 0; i < std::max(1, reps / 3); ++i)
      row.factorization =
          std::min(row.factorization, median_seconds(1, [&] { chol.factorize(K); }));
    g_thread_clock = thread_clock;
  }
  row.nnz_L = chol.factor_nonzeros();
  const fem::Vector b = fem::Vector::Ones(row.free_dofs);
  row.solve = median_seconds(reps, [&] { chol.solve(b); });
  {
    // The same solve with the factor in single precision, and what it costs in accuracy.
    fem::CholmodSolver single(solid.pattern());
    single.set_single_precision(true);
    single.factorize(K);
    const double t = median_seconds(reps, [&] { single.solve(b); });
    const fem::Vector x64 = chol.solve(b), x32 = single.solve(b);
    std::printf("  refinement %d: solve in single precision %.3f ms, relative difference %.2e\n",
                refinement, t * 1e3, (x32 - x64).norm() / x64.norm());
  }

  // Dynamic steps: SG 3 N from the settled state, then at rest (activations off, after the
  // relaxation has settled is not needed: a fresh integrator at the settled state is at rest).
  auto run_steps = [&](bool active, int count, double& iterations, double& factorizations) {
    run.restart();
    const fem::Vector off = fem::Vector::Zero(run.num_muscles());
    const fem::Vector levels = active ? built.activations.levels_at(s.analysis.dt) : off;
    // The first steps at rest iterate once to move from the settling's tolerance to the
    // dynamic one: not counted.
    if (!active)
      for (int k = 0; k < 3; ++k) run.step(s.analysis.dt, off);
    int its = 0, facts = 0;
    const double start = now_seconds();
    for (int k = 0; k < count; ++k) {
      const fem::StepReport rep = run.step(s.analysis.dt, levels).report;
      if (!rep.converged) throw std::runtime_error("step failed: " + rep.message);
      its += rep.iterations;
      facts += rep.factorizations;
    }
    iterations = static_cast<double>(its) / count;
    factorizations = static_cast<double>(facts) / count;
    return (now_seconds() - start) / count;
  };
  double rest_its = 0.0, rest_facts = 0.0;
  row.step_active = run_steps(true, steps, row.iterations_per_step, row.factorizations_per_step);
  row.step_rest = run_steps(false, steps, rest_its, rest_facts);
  std::printf("rest: %.2f it/step %.2f fact/step\n", rest_its, rest_facts);
  return row;
}

// Least-squares slope of log(y) against log(x).
double fitted_exponent(const std::vector<Row>& rows, double Row::*field) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(rows.size());
  for (const Row& r : rows) {
    const double x = std::log(static_cast<double>(r.elements)), y = std::log(r.*field);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

int run(int argc, char** argv) {
  int max_refinement = 2, steps = 30, reps = 15, threads = 1;
  bool wall = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--wall") {
      wall = true;
      continue;
    }
    auto value = [&] {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return std::stoi(argv[++i]);
    };
    if (a == "--max-refinement")
      max_refinement = value();
    else if (a == "--steps")
      steps = std::max(1, value());
    else if (a == "--reps")
      reps = std::max(1, value());
    else if (a == "--threads")
      threads = value();
    else
      throw std::invalid_argument("unknown option '" + a + "'");
  }
  g_thread_clock = threads == 1 && !wall;
  const scene::Scene base =
      scene::read_scene(std::string(TONGUE_SOURCE_DIR) + "/scenes/tongue_sg_3n.yaml");
  std::vector<Row> rows;
  std::printf("%3s %6s %6s %6s %8s %10s %10s %10s %10s %9s %8s %6s %6s %9s\n", "ref", "nodes",
              "hex", "dofs", "nnz(L)", "resid[ms]", "r_act[ms]", "tang[ms]", "factor[ms]",
              "solve[ms]", "step[ms]", "it/st", "fa/st", "rest[ms]");
  for (int refinement = 1; refinement <= max_refinement; ++refinement) {
    const Row r = measure(base, refinement, steps, reps, threads);
    rows.push_back(r);
    std::printf(
        "%3d %6d %6d %6d %7.2fM %10.3f %10.3f %10.2f %10.1f %9.3f %8.2f %6.2f %6.2f %9.3f\n",
        r.refinement, r.nodes, r.elements, r.free_dofs, r.nnz_L * 1e-6, r.residual * 1e3,
        r.residual_active * 1e3, r.tangent * 1e3, r.factorization * 1e3, r.solve * 1e3,
        r.step_active * 1e3, r.iterations_per_step, r.factorizations_per_step, r.step_rest * 1e3);
    std::fflush(stdout);
  }
  if (rows.size() >= 2) {
    std::printf("fitted exponent p in cost ~ elements^p:\n");
    std::printf("  residual %.2f, residual + tangent %.2f, factorization %.2f, solve %.2f\n",
                fitted_exponent(rows, &Row::residual), fitted_exponent(rows, &Row::tangent),
                fitted_exponent(rows, &Row::factorization), fitted_exponent(rows, &Row::solve));
    std::printf("  dynamic step (SG 3 N) %.2f, step at rest %.2f\n",
                fitted_exponent(rows, &Row::step_active), fitted_exponent(rows, &Row::step_rest));
  }
  std::printf("(dt = 4 ms: real time needs a step under 4 ms; %d thread%s, %s)\n", threads,
              threads > 1 ? "s" : "", g_thread_clock ? "thread CPU time" : "wall time");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tongue_scaling_benchmark: %s\n", e.what());
    return 1;
  }
}
