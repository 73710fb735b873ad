#include "fem/integrator/static_solver.hpp"

#include "fem/assembly/rigid_motions.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <sstream>

namespace tongue::fem {

namespace {

// Equilibrium at a fixed load factor, over the free dofs.
class StaticProblem : public NonlinearProblem {
 public:
  StaticProblem(const MechanicalSystem& system, Vector u_template, double load_factor)
      : system_(system), u_(std::move(u_template)), load_factor_(load_factor) {}

  std::shared_ptr<const SparsityPattern> pattern() const override {
    return system_.solid().pattern();
  }
  bool residual(const Vector& x, Vector& r) override { return evaluate(x, r, nullptr); }
  bool residual_and_tangent(const Vector& x, Vector& r, SymmetricMatrix& K) override {
    return evaluate(x, r, &K);
  }
  double force_scale() const override { return load_norm_; }
  void rank_one_terms(const Vector& x, std::vector<RankOneTerm>& terms) override {
    system_.rank_one_terms(full(x), terms);
  }
  const Vector& full(const Vector& x) {
    system_.solid().dofs().scatter_free(x, u_);
    return u_;
  }

 private:
  bool evaluate(const Vector& x, Vector& r, SymmetricMatrix* K) {
    Vector r_full;
    if (!system_.residual(full(x), load_factor_, r_full, K, &load_norm_).ok) return false;
    r = system_.solid().dofs().gather_free(r_full);
    return true;
  }
  const MechanicalSystem& system_;
  Vector u_;
  double load_factor_;
  double load_norm_ = 0.0;
};

}  // namespace

// Beyond this many parts of the load a cut would leave increments that a double cannot tell apart.
constexpr std::int64_t kMostParts = std::int64_t{1} << 50;

StaticReport solve_static(const MechanicalSystem& system, Vector& u, const StaticSettings& settings,
                          const IncrementObserver& observer) {
  StaticReport report;
  const DofMap& dofs = system.solid().dofs();
  if (settings.require_held) {
    std::vector<PrescribedDof> prescribed;
    for (int dof : dofs.prescribed_dofs()) prescribed.push_back({dof / 3, dof % 3, 0.0});
    const std::vector<std::string> free =
        free_rigid_motions(system.solid().mesh().nodes, prescribed);
    if (!free.empty()) {
      report.message = "the model is free to move as a rigid body (";
      for (std::size_t i = 0; i < free.size(); ++i) report.message += (i ? "; " : "") + free[i];
      report.message += "): its constraints must hold it for a static solution";
      return report;
    }
  }
  NewtonSolver newton(system.solid().pattern(), settings.newton);
  // The load factor counted in increments of 1 / parts, parts = load_steps 2^cuts, so that it
  // is i / load_steps exactly and ends at 1 (adding 0.1 ten times gives 0.9999999999999999).
  std::int64_t reached = 0;
  std::int64_t parts = std::max(1, settings.load_steps);
  double lambda = 0.0;
  int cuts_in_row = 0;
  StepReport pending;  // cuts accumulate here until an increment is accepted
  while (reached < parts) {
    const auto start = std::chrono::steady_clock::now();
    const double target = static_cast<double>(reached + 1) / static_cast<double>(parts);
    Vector trial = u;
    for (int dof : dofs.prescribed_dofs()) trial[dof] = target * dofs.prescribed_values()[dof];
    StaticProblem problem(system, trial, target);
    Vector x = dofs.gather_free(trial);
    const NewtonReport result = newton.solve(problem, x);
    pending.add(result);
    pending.wall_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (result.converged) {
      u = problem.full(x);
      ++reached;
      pending.dt = target - lambda;
      lambda = target;
      pending.time = lambda;
      pending.converged = true;
      report.increments.push_back(pending);
      if (observer) observer(pending, u);
      pending = StepReport{};
      cuts_in_row = 0;
      continue;
    }
    std::ostringstream why;
    why << "load factor " << lambda << " -> " << target << ": " << result.failure;
    if (++cuts_in_row > settings.max_cuts || parts > kMostParts) {
      report.message = why.str() + "; gave up after " + std::to_string(settings.max_cuts) + " cuts";
      return report;
    }
    ++pending.cuts;
    pending.message += (pending.message.empty() ? "" : "; ") + why.str() + ", increment halved";
    reached *= 2;
    parts *= 2;
    newton.invalidate_factor();
  }
  report.converged = true;
  return report;
}

}  // namespace tongue::fem
