#pragma once
// Newton-Raphson with a secant line search (Crisfield 1991, sec. 9.3; the scheme ANSYS and FEBio
// use) and optional reuse of the factorized tangent (modified Newton), re-formed as soon as the
// residual stops falling fast enough.
#include <Eigen/LU>
#include <memory>
#include <string>
#include <vector>

#include "fem/solver/cholmod_solver.hpp"
#include "fem/solver/nonlinear_problem.hpp"

namespace tongue::fem {

struct NewtonSettings {
  // Converged when ||r|| <= max(residual_rtol ||r_0||, residual_atol) and the last correction
  // ||dx|| <= max(increment_rtol ||x - x_0||, increment_atol); or at once when
  // ||r|| <= residual_atol.
  double residual_rtol = 1e-6;
  double residual_atol = 1e-9;  // [N]
  double increment_rtol = 1e-6;
  double increment_atol = 1e-12;  // [m]
  // When > 0, convergence is judged by the error left in x instead of the two tests above:
  // converged when the estimated distance to the solution after a correction dx,
  // rho / (1 - rho) ||dx||_inf with rho the contraction of the corrections (measured in this
  // solve; for its first correction the one carried over from the previous solve with the same
  // factor, at least 1/2), is at most this [m]. Such a correction is taken without evaluating
  // the residual after it (final_residual is then the one before it). The initial guess is
  // still accepted as it is when its residual passes the residual test.
  double displacement_tolerance = 0.0;
  int max_iterations = 25;
  bool line_search = true;
  // Modified Newton: a factorization may serve up to this many iterations (0: full Newton),
  // across steps, and is re-formed when ||r_k+1|| > reform_ratio ||r_k||, unless the
  // displacement decides convergence and the corrections of this solve at least halve
  // (||dx_k+1|| < ||dx_k|| / 2).
  int max_tangent_reuse = 0;
  double reform_ratio = 0.5;
  // With a reused factor, the direction is corrected by up to this many BFGS updates built from
  // the last corrections and residual changes (Matthies & Strang 1979; the inverse update in
  // the two-loop form of Nocedal & Wright 2006, alg. 7.4, with the factor as H_0). They are
  // dropped with the factor. 0: plain modified Newton.
  int quasi_newton_updates = 0;
  // Corrections solved with a single-precision copy of the factor (single_precision_factor.hpp):
  // faster solves; each correction is a little less exact, which a modified Newton iteration
  // judged on the double-precision residual and error estimate absorbs.
  bool single_precision_solve = false;
};

struct NewtonReport {
  bool converged = false;
  int iterations = 0;
  int factorizations = 0;
  int residual_evaluations = 0;
  double initial_residual = 0.0;  // ||r_0|| [N]
  double force_scale = 0.0;       // F of the convergence test [N]
  double final_residual = 0.0;    // at the last iterate evaluated [N]
  double last_increment = 0.0;    // [m]
  double error_estimate = 0.0;    // estimated error left in x [m] (inf: unknown; 0: no iteration)
  double max_shift = 0.0;         // largest tangent shift the factorization needed (0: none)
  std::vector<double> residual_history;
  bool start_evaluable = true;  // false: the residual could not be evaluated at the initial guess
  std::string failure;          // why it did not converge
  double assembly_seconds = 0.0, factorization_seconds = 0.0, solve_seconds = 0.0;
};

class NewtonSolver {
 public:
  NewtonSolver(std::shared_ptr<const SparsityPattern> pattern, NewtonSettings settings);

  // Iterates from x (updated in place; on failure x holds the last iterate). The increment test
  // measures the error left against ||x - origin||, origin defaulting to the initial guess: a
  // caller starting from a predicted x passes the state the prediction started from.
  NewtonReport solve(NonlinearProblem& problem, Vector& x, const Vector* origin = nullptr);
  // Forces a fresh tangent at the next iteration (the problem's tangent changed, e.g. new dt).
  void invalidate_factor() { forget_factor(); }
  // Forms and factorizes the problem's tangent at x ahead of the first solve, which then starts
  // with it (a start-up cost moved out of the first solve). The report has the work's figures
  // (one residual and tangent, one factorization) and converged = whether the factor is ready;
  // when not, the next solve forms its own.
  NewtonReport prepare(NonlinearProblem& problem, const Vector& x);

  const NewtonSettings& settings() const { return settings_; }
  NewtonSettings& settings() { return settings_; }

 private:
  NewtonSettings settings_;
  SymmetricMatrix tangent_;
  CholmodSolver linear_solver_;
  int factor_age_ = -1;  // iterations served by the current factor; -1 when none
  // ||dx_k+1||_inf / ||dx_k||_inf last measured with the current factor; < 0 when unknown.
  double contraction_ = -1.0;
  // BFGS pairs since the last factorization: s = x_k+1 - x_k, y = r_k+1 - r_k, 1 / (y . s).
  struct Update {
    Vector s, y;
    double inverse_curvature;
  };
  std::vector<Update> updates_;
  // Rank-one corrections of the reused factor A for the problem's rank-one terms that changed
  // since it was formed (contact springs engaging, +k v v^T, releasing, -k v v^T, or stiffening
  // or softening by a large factor, +(k - k0) v v^T), solved by the Sherman-Morrison-Woodbury
  // formula (Golub & Van Loan 2013, sec. 2.1.4) between the halves of the factor's solve: with
  // A = P^T L L^T P and W = L^-1 P U,
  //   (A + U D U^T)^-1 = P^T L^-T (I - W (D^-1 + W^T W)^-1 W^T) L^-1 P.
  // A column of W is a forward substitution of a vector with three nonzeros, which reaches only
  // the supernodes on one path of the elimination tree: a few per cent of a solve, and sparse
  // (CholmodSolver::forward_sparse). Columns are kept while A lives, with their inner products
  // (D holds the stiffness changes, which need no solve).
  std::vector<RankOneTerm> factored_terms_;  // the terms A holds
  struct Column {
    std::array<int, 3> index;
    Vec3 direction;
    SparseColumn w;  // L^-1 P u
  };
  std::vector<Column> columns_;  // every column of W solved for with this factor
  // gram_[i][j] = w_i . w_j for j <= i, over columns_, NaN until a capacitance system needs it.
  std::vector<std::vector<double>> gram_;
  struct Correction {
    int column;        // in columns_
    double stiffness;  // the change of k along the column's direction [N/m], non-zero
  };
  std::vector<Correction> corrections_;               // in force: U, D and Z
  Eigen::PartialPivLU<Eigen::MatrixXd> capacitance_;  // D^-1 + U^T Z
  std::vector<RankOneTerm> terms_;                    // scratch
  // The terms at the next iterate, when same_engaged_terms has found them already.
  std::vector<RankOneTerm> next_terms_;
  bool next_terms_known_ = false;
  std::vector<RankOneTerm> candidates_;  // terms not engaged at the current iterate
  void split_terms();                    // moves the terms of terms_ not engaged to candidates_
  // Whether the terms engaged at `at` (the next iterate) are on the same unknowns as those of
  // terms_. A BFGS pair taken across a spring that engaged or released would hold the spring's
  // jump as curvature.
  bool same_engaged_terms(NonlinearProblem& problem, const Vector& at);
  // The problem's terms at x into terms_: those same_engaged_terms found, when it did.
  void take_terms(NonlinearProblem& problem, const Vector& x);
  // Brings corrections_ up to the problem's engaged terms at x; false when more would be
  // needed than re-forming the factor costs.
  bool correct_factor(NonlinearProblem& problem, const Vector& x, NewtonReport& report);
  // Adds a change of stiffness along a term's direction, solving for its column of Z unless
  // known.
  void add_correction(const RankOneTerm& term, double stiffness);
  void update_capacitance();
  // Engages the candidate terms that the correction dx would carry past their gap (a node
  // moving into an obstacle) and solves again with them, a few rounds at most. forward_r:
  // L^-1 P r when direction() left it (empty otherwise).
  void engage_candidates(const Vector& r, Vector& dx, Vector forward_r);
  // Counts and times the residual evaluations of one solve.
  struct Residuals {
    NonlinearProblem& problem;
    NewtonReport& report;
    bool operator()(const Vector& at, Vector& out) const;
  };
  // -H r: the factor's solve with its rank-one corrections, corrected by the BFGS updates.
  // Without BFGS updates the solve's forward half L^-1 P r is left in forward_r when given
  // (emptied otherwise), for a solve of r plus a few springs' pulls to start from.
  Vector direction(const Vector& r, Vector* forward_r = nullptr) const;
  // The rest of the corrected solve from y = L^-1 P b: P^T L^-T (I - W C^-1 W^T) y.
  Vector corrected_backward(Vector y) const;
  // Forms and factorizes the tangent at x (and the residual r with it); false with
  // report.failure set when either fails.
  bool refactorize(NonlinearProblem& problem, const Vector& x, Vector& r, NewtonReport& report);
  // Keeps the BFGS pair (s, y), the oldest one dropped beyond quasi_newton_updates.
  void remember(Vector s, Vector y);
  // Chooses eta along dx from x; x_trial = x + eta dx and r_trial its residual. 0 when no step
  // along dx can be evaluated.
  double line_search(const Residuals& evaluate, const Vector& x, const Vector& dx, const Vector& r,
                     Vector& x_trial, Vector& r_trial) const;
  void forget_factor();
};

}  // namespace tongue::fem
