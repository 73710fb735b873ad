// Cost of the FEM core on a tongue-sized box and its x2 refinement (docs/speed.md): the sparse
// factorization's size and flops, the time of each part of a Newton iteration, and the real-time
// factor of a short Newmark run with full Newton and with a reused factorization.
//
// Box 60 x 20 x 20 mm clamped at x = 0, five-parameter Mooney-Rivlin (Gerard et al. 2003) with
// mean dilatation, gravity along -z, Rayleigh damping beta_R = 0.028 s, Newmark dt = 1 ms,
// starting at rest (the tongue drops under its weight).
//
// Usage: fem_box_benchmark [--steps N] [--reps N] [--coarse-only | --refine-only]
// (defaults: 20 steps on each mesh, 5 repetitions of each timing, 3 on the fine mesh).
// The solver runs OpenBLAS on one thread, the setting of the figures in docs/speed.md.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/assembly/loads.hpp"
#include "fem/assembly/solid_model.hpp"
#include "fem/integrator/mechanical_system.hpp"
#include "fem/integrator/newmark_integrator.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"
#include "fem/solver/cholmod_solver.hpp"

namespace {

using namespace tongue::fem;
using Clock = std::chrono::steady_clock;

constexpr double kLength = 0.060, kWidth = 0.020, kHeight = 0.020;  // m
constexpr double kDensity = 1040.0;                                 // kg/m^3
constexpr double kGravity = 9.81;                                   // m/s^2
constexpr double kDt = 1e-3;                                        // s
constexpr double kRayleighBeta = 0.028;                             // s
constexpr int kReuse = 10;  // max_tangent_reuse of the modified-Newton run

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

template <class F>
double median_seconds(int reps, F&& f) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const auto start = Clock::now();
    f();
    t.push_back(seconds_since(start));
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}

struct DynamicResult {
  int steps = 0;
  bool converged = true;
  int iterations = 0, factorizations = 0;
  double wall_seconds = 0.0, max_step_seconds = 0.0;
  double assembly_seconds = 0.0, factorization_seconds = 0.0, solve_seconds = 0.0;
  double tip_deflection = 0.0;  // z displacement of the free end's centre [m]
  Vector u;
};

struct MeshResult {
  int nx = 0, ny = 0, nz = 0;
  int nodes = 0, elements = 0, free_dofs = 0, pattern_nnz = 0;
  double nnz_L = 0.0, gflop = 0.0, analysis_seconds = 0.0;
  double residual_seconds = 0.0, assembly_seconds = 0.0, factorization_seconds = 0.0,
         solve_seconds = 0.0;
  DynamicResult full, reuse;
  double reuse_difference = 0.0;  // max |u_full - u_reuse| at the end [m]
};

std::shared_ptr<const SolidModel> make_model(int nx, int ny, int nz) {
  Mesh mesh = make_box(Vec3::Zero(), Vec3(kLength, kWidth, kHeight), nx, ny, nz);
  std::vector<PrescribedDof> clamp;
  for (int n : mesh.node_set("x_min")) {
    for (int c = 0; c < 3; ++c) clamp.push_back({n, c, 0.0});
  }
  return std::make_shared<const SolidModel>(std::move(mesh), make_material("mooney_rivlin5", {}),
                                            Formulation::mean_dilatation, kDensity, clamp);
}

// The node at the centre of the free end (x = L, y = W/2, z = H/2; ny, nz even) or next to it.
int tip_node(int nx, int ny, int nz) {
  return nx + (nx + 1) * (ny / 2 + (ny + 1) * (nz / 2));
}

DynamicResult run_dynamic(MechanicalSystem& system, int steps, int max_tangent_reuse, int tip) {
  DynamicSettings settings;
  settings.damping.stiffness_coefficient = kRayleighBeta;
  settings.newton.max_tangent_reuse = max_tangent_reuse;
  NewmarkIntegrator integrator(system, settings);
  DynamicResult result;
  result.steps = steps;
  for (int s = 0; s < steps; ++s) {
    const StepReport r = integrator.step(kDt);
    result.converged = result.converged && r.converged;
    result.iterations += r.iterations;
    result.factorizations += r.factorizations;
    result.wall_seconds += r.wall_seconds;
    result.max_step_seconds = std::max(result.max_step_seconds, r.wall_seconds);
    result.assembly_seconds += r.assembly_seconds;
    result.factorization_seconds += r.factorization_seconds;
    result.solve_seconds += r.solve_seconds;
    if (!r.converged) {
      std::fprintf(stderr, "  step %d did not converge: %s\n", s, r.message.c_str());
      break;
    }
  }
  result.u = integrator.displacement();
  result.tip_deflection = result.u[3 * tip + 2];
  return result;
}

MeshResult run_mesh(int nx, int ny, int nz, int steps, int reps) {
  MeshResult m;
  m.nx = nx, m.ny = ny, m.nz = nz;
  std::fprintf(stderr, "%d x %d x %d: setting up\n", nx, ny, nz);
  const auto model = make_model(nx, ny, nz);
  m.nodes = model->mesh().num_nodes();
  m.elements = model->mesh().num_elements();
  m.free_dofs = model->dofs().num_free();
  m.pattern_nnz = model->pattern()->nnz();

  CholmodSolver solver(model->pattern());
  m.analysis_seconds = solver.analysis_seconds();

  // One Newton iteration's parts at a bent state, on the Newmark effective tangent
  // K + c0 M + c1 C with C = beta_R K (what the dynamic run factorizes).
  Vector u = Vector::Zero(model->num_dofs());
  for (int n = 0; n < m.nodes; ++n) {
    const double t = model->mesh().nodes[n].x() / kLength;
    u[3 * n + 2] = -2e-3 * t * t;
  }
  const SymmetricMatrix mass = model->mass_matrix(false);
  SymmetricMatrix K(model->pattern());
  Vector f;
  std::fprintf(stderr, "%d x %d x %d: timing one Newton iteration (%d repetitions)\n", nx, ny, nz,
               reps);
  m.residual_seconds = median_seconds(reps, [&] { model->assemble(u, f, nullptr); });
  m.assembly_seconds = median_seconds(reps, [&] {
    if (!model->assemble(u, f, &K).ok) throw std::runtime_error("inverted element");
  });
  const double c0 = 4.0 / (kDt * kDt), c1 = 2.0 / kDt;
  K.scale_and_add(1.0 + c1 * kRayleighBeta, c0, mass);
  m.factorization_seconds = median_seconds(reps, [&] {
    if (!solver.factorize(K).ok) throw std::runtime_error("factorization failed");
  });
  m.nnz_L = solver.factor_nonzeros();
  m.gflop = solver.factorization_flops() * 1e-9;
  const Vector b = model->dofs().gather_free(f);
  m.solve_seconds = median_seconds(std::max(reps, 5), [&] { (void)solver.solve(b); });

  MechanicalSystem system(model);
  system.add_load(
      std::make_shared<ConstantForce>("gravity", model->body_force(Vec3(0, 0, -kGravity))));
  const int tip = tip_node(nx, ny, nz);
  std::fprintf(stderr, "%d x %d x %d: %d dynamic steps, full Newton\n", nx, ny, nz, steps);
  m.full = run_dynamic(system, steps, 0, tip);
  std::fprintf(stderr, "%d x %d x %d: %d dynamic steps, tangent reuse %d\n", nx, ny, nz, steps,
               kReuse);
  m.reuse = run_dynamic(system, steps, kReuse, tip);
  m.reuse_difference = (m.full.u - m.reuse.u).lpNorm<Eigen::Infinity>();
  return m;
}

// The table: one row per quantity, one column per mesh.
void row(const char* label, const std::vector<MeshResult>& r,
         const std::function<std::string(const MeshResult&)>& cell) {
  std::printf("%-44s", label);
  for (const MeshResult& m : r) std::printf("%16s", cell(m).c_str());
  std::printf("\n");
}

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

void dynamic_rows(const char* title, const std::vector<MeshResult>& r,
                  DynamicResult MeshResult::*which) {
  std::printf("%s\n", title);
  row("  steps of 1 ms, all converged", r, [&](const MeshResult& m) {
    const DynamicResult& d = m.*which;
    return std::to_string(d.steps) + (d.converged ? " yes" : " NO");
  });
  row("  Newton iterations / step", r, [&](const MeshResult& m) {
    const DynamicResult& d = m.*which;
    return fmt("%.2f", static_cast<double>(d.iterations) / d.steps);
  });
  row("  factorizations / step", r, [&](const MeshResult& m) {
    const DynamicResult& d = m.*which;
    return fmt("%.2f", static_cast<double>(d.factorizations) / d.steps);
  });
  row("  wall time / step, mean [ms]", r, [&](const MeshResult& m) {
    const DynamicResult& d = m.*which;
    return fmt("%.1f", 1e3 * d.wall_seconds / d.steps);
  });
  row("  wall time / step, worst [ms]", r,
      [&](const MeshResult& m) { return fmt("%.1f", 1e3 * (m.*which).max_step_seconds); });
  row("  of which assembly / factor. / solve [%]", r, [&](const MeshResult& m) {
    const DynamicResult& d = m.*which;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.0f/%.0f/%.0f", 100 * d.assembly_seconds / d.wall_seconds,
                  100 * d.factorization_seconds / d.wall_seconds,
                  100 * d.solve_seconds / d.wall_seconds);
    return std::string(buf);
  });
  row("  real-time factor [simulated s / wall s]", r, [&](const MeshResult& m) {
    const DynamicResult& d = m.*which;
    return fmt("%.3f", d.steps * kDt / d.wall_seconds);
  });
  row("  tip deflection at the end [mm]", r,
      [&](const MeshResult& m) { return fmt("%.4f", 1e3 * (m.*which).tip_deflection); });
}

int parse_count(int argc, char** argv, int& i) {
  if (i + 1 >= argc) throw std::invalid_argument(std::string(argv[i]) + " needs a number");
  const int n = std::atoi(argv[++i]);
  if (n < 1) throw std::invalid_argument(std::string(argv[i - 1]) + " needs a positive number");
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 20, reps = 5;
  bool coarse = true, fine = true;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--steps") {
        steps = parse_count(argc, argv, i);
      } else if (a == "--reps") {
        reps = parse_count(argc, argv, i);
      } else if (a == "--refine-only") {
        coarse = false;
      } else if (a == "--coarse-only") {
        fine = false;
      } else {
        throw std::invalid_argument("unknown option " + a);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr,
                 "%s\nusage: %s [--steps N] [--reps N] "
                 "[--coarse-only | --refine-only]\n",
                 e.what(), argv[0]);
    return 2;
  }

  std::vector<MeshResult> results;
  try {
    if (coarse) results.push_back(run_mesh(15, 7, 7, steps, reps));
    if (fine) results.push_back(run_mesh(30, 14, 14, steps, std::min(reps, 3)));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "benchmark failed: %s\n", e.what());
    return 1;
  }

  std::printf(
      "\nBox 60 x 20 x 20 mm clamped at x = 0; mooney_rivlin5, mean dilatation; rho = 1040 "
      "kg/m^3;\ngravity 9.81 m/s^2 along -z; Newmark dt = 1 ms; Rayleigh beta_R = 0.028 s; "
      "CHOLMOD supernodal;\none BLAS thread (set by the solver); one assembly thread. Times: "
      "median of repetitions.\n\n");
  row("mesh [hex per direction]", results, [](const MeshResult& m) {
    return std::to_string(m.nx) + "x" + std::to_string(m.ny) + "x" + std::to_string(m.nz);
  });
  row("nodes", results, [](const MeshResult& m) { return std::to_string(m.nodes); });
  row("elements [hex8]", results, [](const MeshResult& m) { return std::to_string(m.elements); });
  row("free dofs", results, [](const MeshResult& m) { return std::to_string(m.free_dofs); });
  row("nnz(pattern), upper triangle", results,
      [](const MeshResult& m) { return std::to_string(m.pattern_nnz); });
  row("nnz(L) [M]", results, [](const MeshResult& m) { return fmt("%.3f", m.nnz_L * 1e-6); });
  row("factorization [GFLOP]", results, [](const MeshResult& m) { return fmt("%.3f", m.gflop); });
  row("symbolic analysis [ms]", results,
      [](const MeshResult& m) { return fmt("%.1f", 1e3 * m.analysis_seconds); });
  std::printf("per Newton iteration\n");
  row("  residual only [ms]", results,
      [](const MeshResult& m) { return fmt("%.2f", 1e3 * m.residual_seconds); });
  row("  residual + tangent [ms]", results,
      [](const MeshResult& m) { return fmt("%.2f", 1e3 * m.assembly_seconds); });
  row("  numeric factorization [ms]", results,
      [](const MeshResult& m) { return fmt("%.1f", 1e3 * m.factorization_seconds); });
  row("  factorization rate [GFLOP/s]", results,
      [](const MeshResult& m) { return fmt("%.2f", m.gflop / m.factorization_seconds); });
  row("  solve with the factor [ms]", results,
      [](const MeshResult& m) { return fmt("%.2f", 1e3 * m.solve_seconds); });
  dynamic_rows("dynamics, full Newton", results, &MeshResult::full);
  dynamic_rows("dynamics, factorization reused (max 10 iterations)", results, &MeshResult::reuse);
  row("max |u_full - u_reuse| at the end [nm]", results,
      [](const MeshResult& m) { return fmt("%.3g", 1e9 * m.reuse_difference); });
  bool ok = true;
  for (const MeshResult& m : results) ok = ok && m.full.converged && m.reuse.converged;
  return ok ? 0 : 1;
}
