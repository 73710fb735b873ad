#pragma once
// The Newmark dynamics of fem::NewmarkIntegrator in reduced coordinates: u = origin + Phi q, the
// equations of motion projected onto the modes (Galerkin),
//   M_r q'' + C_r q' + Phi^T (f_int(u) - f_ext(u)) = 0,  M_r = Phi^T M Phi,
//   C_r = alpha M_r + beta_R Phi^T K0 Phi,
// stepped by the same Newmark rule and solved by Newton on the k reduced coordinates with a
// dense factor of the reduced tangent, reused across iterations and steps as the full solver
// does; with the scene's quasi_newton_updates > 0 (the dynamic default) each correction and the
// residual's change over it update the dense matrix by BFGS, so that it is formed again (an
// assembly and a projection, about 20 reduced residuals on the tongue) only when the updated
// matrix still converges slowly. The solid's internal force is integrated over the basis' sample of
// elements with their weights (energy-conserving sampling and weighting: Farhat, Avery, Chapman &
// Cortial 2014, Int. J. Numer. Meth. Eng. 98); the loads, the muscles' fibre forces and their
// active stiffening among them, are evaluated on the whole reconstructed displacement and projected
// exactly; the sample's force is corrected by a constant, its difference from the mesh's at the
// origin, so that the origin stays an equilibrium. The modes are zero at the prescribed dofs (every
// snapshot is), so u keeps the origin's prescribed values. When the scene's solver solves in
// single precision (newton.single_precision_solve, the dynamic default), so do the two products
// with the basis of every iteration (Phi^T r, Phi dq): their round-off (about 1e-7 of the
// magnitudes summed) moves the converged state by far less than the step's tolerance.
#include <Eigen/Cholesky>
#include <memory>
#include <optional>

#include "fem/integrator/mechanical_system.hpp"
#include "fem/integrator/newmark_integrator.hpp"
#include "fem/integrator/step_report.hpp"
#include "fem/integrator/time_integrator.hpp"
#include "reduced/full_model_check.hpp"
#include "reduced/galerkin_projector.hpp"
#include "reduced/reduced_basis_file.hpp"

namespace tongue::reduced {

class ReducedIntegrator : public fem::TimeIntegrator {
 public:
  // The basis must fit the system's mesh (check_fits). Throws std::invalid_argument when its
  // sizes do not fit or a mode moves a prescribed dof.
  ReducedIntegrator(const fem::MechanicalSystem& system, ReducedBasis basis,
                    fem::DynamicSettings settings);

  // The state nearest u0, v0 in the basis (their projections: the modes are orthonormal), the
  // consistent reduced acceleration, K0 for the damping. Throws std::runtime_error when the
  // forces cannot be evaluated there.
  void initialize(const fem::Vector& u0, const fem::Vector& v0, double t0 = 0.0) override;
  // Forms and factorizes the reduced tangent of a step of dt at the predictor.
  fem::StepReport prepare(double dt) override;
  // Advances by dt; cuts and retries on failure like fem::NewmarkIntegrator::step.
  fem::StepReport step(double dt) override;
  // As fem::NewmarkIntegrator: the last step needed no correction and nothing moves faster than
  // fem::NewmarkIntegrator::kRestSpeed.
  bool at_rest() const override;
  fem::StepReport hold(double dt) override;

  // The error indicator of the current state (FullModelCheck), the loads as they stand (the
  // last step's activations); 0 before the first step.
  double full_model_correction();

  // Full vectors, reconstructed from the reduced state.
  const fem::Vector& displacement() const override { return u_; }
  const fem::Vector& velocity() const override { return v_; }
  const fem::Vector& acceleration() const override { return a_; }
  double time() const override { return t_; }
  int num_modes() const { return static_cast<int>(phi_.cols()); }
  int num_sampled_elements() const { return num_sampled_; }

 private:
  struct Step;
  bool advance(double dt, fem::StepReport& report, int depth);
  // f += Phi^T r and Phi dq over the free dofs, in the products' precision.
  void project_free(const fem::Vector& r_free, fem::Vector& f) const;
  fem::Vector expand_free(const fem::Vector& dq) const;
  // origin + Phi q [m].
  fem::Vector displacement_of(const fem::Vector& q) const;
  // Phi^T r(u) with the sample's weights, u the full displacement; false at an inverted element.
  bool reduced_force(const fem::Vector& u, fem::Vector& f, fem::SymmetricMatrix* K,
                     double* load_norm) const;
  bool form_tangent(const fem::Vector& q, double dt);
  // The Newton matrix and its factor updated by the BFGS pair (s: a correction, y: the
  // residual's change over it); left as they are when the pair would not keep them positive
  // definite.
  void update_tangent(const fem::Vector& s, const fem::Vector& y);
  void reconstruct();

  const fem::MechanicalSystem& system_;
  fem::DynamicSettings settings_;
  // Of the basis' products and the Newton matrix's projection: the scene's solve precision
  // (newton.single_precision_solve).
  Precision precision_;
  Eigen::MatrixXd phi_;  // all dofs x k
  fem::Vector origin_;   // the basis' origin, full vector [m]
  int num_sampled_ = 0;
  Eigen::MatrixXd phi_free_;  // free dofs x k
  // phi_free_ in single precision, for the products of every iteration in single precision;
  // empty otherwise.
  Eigen::MatrixXf phi_free_single_;
  GalerkinProjector projector_;    // Phi^T A Phi
  std::vector<double> weights_;    // per element: the sample's weight, 0 elsewhere
  fem::Vector origin_correction_;  // Phi^T (f_int - f_int of the sample) at the origin
  fem::SymmetricMatrix mass_;
  Eigen::MatrixXd mass_r_, damping_r_;
  std::optional<fem::SymmetricMatrix> stiffness0_;  // K0 over the free dofs, for C
  fem::Vector damping_state_;                       // the state K0 was taken at
  std::unique_ptr<FullModelCheck> check_;           // made at the first full_model_correction()
  double last_dt_ = 0.0;
  Eigen::MatrixXd newton_matrix_;         // the reduced tangent of the step, BFGS-updated
  Eigen::LDLT<Eigen::MatrixXd> tangent_;  // its factor
  double tangent_dt_ = 0.0;               // 0: no factor
  double contraction_ = -1.0;
  fem::Vector q_, qd_, qdd_;
  fem::Vector u_, v_, a_;
  double t_ = 0.0;
  bool in_equilibrium_ = false;
};

}  // namespace tongue::reduced
