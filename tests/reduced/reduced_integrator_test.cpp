// The reduced dynamics against the full model on a cantilever: trained on the response to one
// tip load, the reduced model (its POD basis, its sampled elements) reproduces the full model's
// response to another, rests where the full model rests, and the correction the full model
// would make to its state says when it leaves what it was trained on.
#include "reduced/reduced_integrator.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <memory>

#include "fem/integrator/newmark_integrator.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"
#include "reduced/element_reduced_forces.hpp"
#include "reduced/element_sampling.hpp"
#include "reduced/pod_basis.hpp"

namespace tongue::reduced {
namespace {

// A tip load whose size the test sets between steps.
class TipLoad : public fem::ForceContribution {
 public:
  explicit TipLoad(fem::Vector force) : force_(std::move(force)) {}
  std::string name() const override { return "tip"; }
  void add(const fem::Vector&, double load_factor, fem::Vector& force,
           fem::SymmetricMatrix*) const override {
    force += load_factor * scale * force_;
  }
  double scale = 0.0;

 private:
  fem::Vector force_;
};

constexpr double kDt = 2e-3;  // s
constexpr int kSteps = 60;    // 0.12 s: about two periods of the first bending mode

struct Cantilever {
  // 60 x 10 x 10 mm of a soft neo-Hookean solid (5 kPa, tongue-like), clamped at x = 0, a
  // downward tip load.
  Cantilever() {
    fem::Mesh mesh = fem::make_box(fem::Vec3::Zero(), {0.06, 0.01, 0.01}, 6, 2, 2);
    std::vector<fem::PrescribedDof> clamp;
    for (int node : mesh.node_sets.at("x_min"))
      for (int c = 0; c < 3; ++c) clamp.push_back({node, c, 0.0});
    fem::Vector tip = fem::Vector::Zero(3 * mesh.num_nodes());
    const auto& end = mesh.node_sets.at("x_max");
    for (int node : end) tip[3 * node + 2] = -0.02 / static_cast<double>(end.size());  // N
    solid = std::make_shared<fem::SolidModel>(
        std::move(mesh),
        fem::make_material("neo_hookean", {{"shear_modulus", 5000.0}, {"poisson_ratio", 0.45}}),
        fem::Formulation::mean_dilatation, 1000.0, clamp);
    system = std::make_unique<fem::MechanicalSystem>(solid);
    load = std::make_shared<TipLoad>(tip);
    system->add_load(load);
    settings.damping.mass_coefficient = 5.0;  // 1/s
    settings.newton.max_tangent_reuse = 20;
  }
  // The full model's displacements under a tip load of the given scale, from rest.
  std::vector<fem::Vector> full_run(double scale) {
    fem::NewmarkIntegrator full(*system, settings);
    load->scale = 0.0;  // from rest: the load acts from the first step on
    full.initialize(fem::Vector::Zero(solid->num_dofs()), fem::Vector::Zero(solid->num_dofs()));
    load->scale = scale;
    std::vector<fem::Vector> u;
    for (int k = 0; k < kSteps; ++k) {
      EXPECT_TRUE(full.step(kDt).converged);
      u.push_back(full.displacement());
    }
    return u;
  }
  std::shared_ptr<fem::SolidModel> solid;
  std::unique_ptr<fem::MechanicalSystem> system;
  std::shared_ptr<TipLoad> load;
  fem::DynamicSettings settings;
};

// The basis of the run under the full tip load, with every element (tolerance 0: all of them,
// weight 1) or a sample.
ReducedBasis train(Cantilever& c, double sampling) {
  const std::vector<fem::Vector> run = c.full_run(1.0);
  Eigen::MatrixXd snapshots(c.solid->num_dofs(), static_cast<Eigen::Index>(run.size()));
  for (std::size_t k = 0; k < run.size(); ++k) snapshots.col(static_cast<Eigen::Index>(k)) = run[k];
  const PodBasis pod = pod_basis(snapshots, 0.99999999);
  ReducedBasis basis;
  basis.origin = fem::Vector::Zero(c.solid->num_dofs());
  basis.modes = pod.modes;
  const int E = c.solid->mesh().num_elements();
  if (sampling > 0.0) {
    const ElementSample sample =
        sample_elements(element_reduced_forces(*c.solid, basis.origin, pod.modes, snapshots),
                        static_cast<int>(pod.modes.cols()), sampling);
    basis.sample_elements = sample.elements;
    basis.sample_weights = sample.weights;
  } else {
    for (int e = 0; e < E; ++e) basis.sample_elements.push_back(e);
    basis.sample_weights = fem::Vector::Ones(E);
  }
  return basis;
}

// The reduced model's run under a tip load of the given scale against the full model's: the
// largest nodal error over the run, relative to the largest tip deflection.
double relative_error(Cantilever& c, const ReducedBasis& basis, double scale,
                      double* largest_indicator = nullptr, int* factorizations = nullptr) {
  const std::vector<fem::Vector> full = c.full_run(scale);
  ReducedIntegrator reduced(*c.system, basis, c.settings);
  c.load->scale = 0.0;
  reduced.initialize(fem::Vector::Zero(c.solid->num_dofs()),
                     fem::Vector::Zero(c.solid->num_dofs()));
  reduced.prepare(kDt);
  c.load->scale = scale;
  double error = 0.0, deflection = 0.0;
  for (int k = 0; k < kSteps; ++k) {
    const fem::StepReport report = reduced.step(kDt);
    EXPECT_TRUE(report.converged) << report.message;
    if (factorizations) *factorizations += report.factorizations;
    error = std::max(error, (reduced.displacement() - full[k]).cwiseAbs().maxCoeff());
    deflection = std::max(deflection, full[k].cwiseAbs().maxCoeff());
    if (largest_indicator)
      *largest_indicator = std::max(*largest_indicator, reduced.full_model_correction());
  }
  EXPECT_GT(deflection, 5e-3);  // the load bends the beam by several millimetres
  return error / deflection;
}

TEST(ReducedIntegrator, ReproducesTheFullModelOnARunItWasNotTrainedOn) {
  Cantilever c;
  const ReducedBasis every_element = train(c, 0.0);
  const ReducedBasis sampled = train(c, 0.01);
  EXPECT_LT(sampled.sample_elements.size(), 24u);  // of the mesh's 24 elements
  // The basis holds all but 1e-8 of the training run's energy, so on that run the reduced model
  // is the full one to the Newton tolerances of both (measured: 3e-4 of the deflection).
  EXPECT_LT(relative_error(c, every_element, 1.0), 1e-3);
  // Under 0.6 of the load, a nonlinear response of another shape that the basis can only
  // approximate (measured: 5e-4 with every element and with the sample). The bounds leave
  // room for the projection's error of a run it was not trained on, and for the sample's 1 %
  // force misfit, not for a wrong projection or weighting, which are off by tens of percent.
  EXPECT_LT(relative_error(c, every_element, 0.6), 2e-3);
  EXPECT_LT(relative_error(c, sampled, 0.6), 5e-3);
}

TEST(ReducedIntegrator, BfgsUpdatesSaveFormingTheTangentAndKeepTheRun) {
  // The reduced tangent is dense and small: with quasi_newton_updates > 0 each pair of a
  // correction and its residual change updates it (BFGS), and it is formed again only when
  // the updated matrix still converges slowly. The run under 0.6 of the trained load, whose
  // stiffening the updates follow, stays as close to the full model's as without them.
  Cantilever c;
  const ReducedBasis basis = train(c, 0.0);
  int plain = 0, updated = 0;
  double indicator = 0.0;
  const double plain_error = relative_error(c, basis, 0.6, &indicator, &plain);
  c.settings.newton.quasi_newton_updates = 8;
  const double updated_error = relative_error(c, basis, 0.6, &indicator, &updated);
  EXPECT_LT(updated, plain);  // measured: 7 re-formations without the updates, none with them
  // Both Newton iterations stop within the same displacement tolerance: the runs differ by a
  // fraction of the basis' own error (measured: 5.2e-4 and 5.6e-4 of the
  // deflection).
  EXPECT_LT(updated_error, 2e-3);
  EXPECT_LT(std::abs(updated_error - plain_error), 1e-3);
}

// A basis of every free dof (a random rotation of the full model's unknowns) and every element
// at weight 1: the reduced equations are the full ones in other coordinates.
ReducedBasis every_mode_and_element(const Cantilever& c) {
  const fem::DofMap& dofs = c.solid->dofs();
  const int n = c.solid->num_dofs(), free = dofs.num_free();
  std::srand(11);
  const Eigen::MatrixXd rotation =
      Eigen::MatrixXd::Random(free, free).householderQr().householderQ();
  ReducedBasis basis;
  basis.origin = fem::Vector::Zero(n);
  basis.modes = Eigen::MatrixXd::Zero(n, free);
  for (int j = 0; j < free; ++j) {
    fem::Vector mode = fem::Vector::Zero(n);
    dofs.scatter_free(rotation.col(j), mode);
    basis.modes.col(j) = mode;
  }
  for (int e = 0; e < c.solid->mesh().num_elements(); ++e) basis.sample_elements.push_back(e);
  basis.sample_weights = fem::Vector::Ones(c.solid->mesh().num_elements());
  return basis;
}

TEST(ReducedIntegrator, WithEveryModeAndElementItIsTheFullModel) {
  // Both solved to 1e-13 m by full Newton, the runs agree to what the solves leave.
  Cantilever c;
  c.settings.newton.max_tangent_reuse = 0;
  c.settings.newton.displacement_tolerance = 1e-13;  // m
  const int n = c.solid->num_dofs();
  const ReducedBasis basis = every_mode_and_element(c);
  const std::vector<fem::Vector> full = c.full_run(0.8);
  ReducedIntegrator reduced(*c.system, basis, c.settings);
  c.load->scale = 0.0;
  reduced.initialize(fem::Vector::Zero(n), fem::Vector::Zero(n));
  c.load->scale = 0.8;
  double largest = 0.0, motion = 0.0;
  for (int k = 0; k < kSteps; ++k) {
    ASSERT_TRUE(reduced.step(kDt).converged);
    largest = std::max(largest, (reduced.displacement() - full[k]).cwiseAbs().maxCoeff());
    motion = std::max(motion, full[k].cwiseAbs().maxCoeff());
  }
  // Measured: 2.8e-11 m over a 45 mm motion, the 1e-13 m a step that each solve leaves carried
  // through 60 steps; a wrong mass, damping, load or projection would be off by percents.
  EXPECT_LT(largest, 1e-8 * motion) << largest << " m of " << motion << " m";
}

// A scene's solver that solves in single precision (its dynamic default) has the reduced model
// take its products with the basis in single precision too: each perturbs the iteration by
// float's round-off, relative to the residual or the correction it maps, far below a scene's
// step tolerance (tens of micrometres at dt 8 ms). Solved to 1 um, the two runs stay within
// what two runs each within 1 um of the same solution can differ by (measured: 2.1e-9 m apart).
TEST(ReducedIntegrator, ProductsInSinglePrecisionKeepTheRunWithinTheTolerance) {
  Cantilever c;
  c.settings.newton.displacement_tolerance = 1e-6;  // m
  const ReducedBasis basis = train(c, 0.05);
  const auto run = [&](bool single) {
    fem::DynamicSettings settings = c.settings;
    settings.newton.single_precision_solve = single;
    ReducedIntegrator reduced(*c.system, basis, settings);
    c.load->scale = 0.0;
    reduced.initialize(fem::Vector::Zero(c.solid->num_dofs()),
                       fem::Vector::Zero(c.solid->num_dofs()));
    c.load->scale = 0.6;
    std::vector<fem::Vector> u;
    for (int k = 0; k < kSteps; ++k) {
      const fem::StepReport report = reduced.step(kDt);
      EXPECT_TRUE(report.converged) << report.message;
      EXPECT_EQ(report.cuts, 0);
      u.push_back(reduced.displacement());
    }
    return u;
  };
  const std::vector<fem::Vector> doubles = run(false), singles = run(true);
  double apart = 0.0, deflection = 0.0;
  for (int k = 0; k < kSteps; ++k) {
    apart = std::max(apart, (singles[k] - doubles[k]).cwiseAbs().maxCoeff());
    deflection = std::max(deflection, doubles[k].cwiseAbs().maxCoeff());
  }
  EXPECT_GT(deflection, 5e-3);
  EXPECT_GT(apart, 0.0);  // the products did change
  EXPECT_LT(apart, 2e-6) << apart << " m";
}

TEST(ReducedIntegrator, APredictionThatInvertsAnElementGivesWayToTheLastState) {
  // The tip's corner node kicked towards the beam so fast that the constant-velocity predictor
  // carries it three elements deep and inverts them, over a step long against the node's own
  // vibration (omega dt in the tens): the step's solution moves it a fraction of a millimetre
  // (measured: 0.13 mm). As in the full model, Newton then starts from the last state instead,
  // and the step needs no cut (without that: 8 cuts).
  Cantilever c;
  c.settings.newton.displacement_tolerance = 1e-12;  // m
  const double dt = 0.05, element = 0.01;            // s, m
  const int n = c.solid->num_dofs();
  fem::Vector v0 = fem::Vector::Zero(n);
  const int corner = c.solid->mesh().node_sets.at("x_max").front();
  v0[3 * corner] = -3.0 * element / dt;  // m/s
  const fem::Vector u0 = fem::Vector::Zero(n);
  c.load->scale = 0.0;
  fem::NewmarkIntegrator full(*c.system, c.settings);
  full.initialize(u0, v0);
  ReducedIntegrator reduced(*c.system, every_mode_and_element(c), c.settings);
  reduced.initialize(u0, v0);
  const fem::StepReport f = full.step(dt);
  const fem::StepReport r = reduced.step(dt);
  ASSERT_TRUE(f.converged) << f.message;
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(f.cuts, 0);
  EXPECT_EQ(r.cuts, 0) << r.message;
  const double moved = full.displacement().cwiseAbs().maxCoeff();
  EXPECT_LT(moved, 0.5 * element);  // far from where the predictor put the node
  // Both solved to 1e-12 m (with every mode the reduced equations are the full ones; measured:
  // 2e-12 m apart).
  EXPECT_LT((reduced.displacement() - full.displacement()).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(ReducedIntegrator, RestsWhereTheFullModelRestsAndHoldsThere) {
  Cantilever c;
  const ReducedBasis sampled = train(c, 0.05);
  ReducedIntegrator reduced(*c.system, sampled, c.settings);
  c.load->scale = 0.0;
  reduced.initialize(fem::Vector::Zero(c.solid->num_dofs()),
                     fem::Vector::Zero(c.solid->num_dofs()));
  // At the origin without load the sample's force is corrected to the mesh's: no motion.
  const fem::StepReport first = reduced.step(kDt);
  ASSERT_TRUE(first.converged);
  EXPECT_EQ(first.iterations, 0);
  EXPECT_LT(reduced.displacement().cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_TRUE(reduced.at_rest());
  EXPECT_TRUE(reduced.hold(kDt).held);
  EXPECT_NEAR(reduced.time(), 2 * kDt, 1e-15);
  EXPECT_LT(reduced.full_model_correction(), 1e-9);
}

TEST(ReducedIntegrator, TheFullResidualGrowsOutsideTheTraining) {
  // Trained on the tip load alone, the basis cannot follow a load across the beam: the full
  // model's residual at the reduced state says so, where on the training run it stays small.
  Cantilever c;
  const ReducedBasis basis = train(c, 0.0);
  double trained = 0.0;
  relative_error(c, basis, 1.0, &trained);
  EXPECT_GT(trained, 0.0);
  fem::Vector sideways = fem::Vector::Zero(c.solid->num_dofs());
  for (int node : c.solid->mesh().node_sets.at("x_max")) sideways[3 * node + 1] = 0.005;
  auto side = std::make_shared<fem::ConstantForce>("side", sideways);
  c.system->add_load(side);
  ReducedIntegrator reduced(*c.system, basis, c.settings);
  c.load->scale = 0.0;
  reduced.initialize(fem::Vector::Zero(c.solid->num_dofs()),
                     fem::Vector::Zero(c.solid->num_dofs()));
  c.load->scale = 1.0;
  double untrained = 0.0;
  for (int k = 0; k < 20; ++k) {
    ASSERT_TRUE(reduced.step(kDt).converged);
    untrained = std::max(untrained, reduced.full_model_correction());
  }
  // Measured: a correction of 0.012 mm at most on the training run (the steps' own Newton
  // tolerances and the modes dropped), 0.23 mm with the sideways load, which the basis cannot
  // follow at all.
  EXPECT_GT(untrained, 5.0 * trained);
}

TEST(ReducedIntegrator, RefusesABasisForAnotherModel) {
  Cantilever c;
  ReducedBasis basis = train(c, 0.0);
  basis.modes.row(0).setConstant(0.1);  // node 0 is clamped
  EXPECT_THROW(ReducedIntegrator(*c.system, basis, c.settings), std::invalid_argument);
  basis.modes.conservativeResize(basis.modes.rows() - 3, Eigen::NoChange);
  EXPECT_THROW(ReducedIntegrator(*c.system, basis, c.settings), std::invalid_argument);
}

TEST(ReducedIntegrator, RefusesTheAlphaMethod) {
  Cantilever c;
  const ReducedBasis basis = train(c, 0.0);
  fem::DynamicSettings settings = c.settings;
  settings.newmark = fem::NewmarkParameters::bossak(0.8);
  EXPECT_THROW(ReducedIntegrator(*c.system, basis, settings), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::reduced
