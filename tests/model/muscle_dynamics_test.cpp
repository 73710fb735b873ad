// A muscle in a dynamic run: a block of tongue tissue clamped at one end with one fibre along
// the middle of its top edge. Activated, the fibre pulls the free end toward the clamp and curls
// the block upward; with the fibre stiffness in the tangent, Newton converges in a few
// iterations per 1 ms step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "fem/integrator/newmark_integrator.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"
#include "model/muscle_forces.hpp"

namespace tongue::model {
namespace {

using fem::Vec3;
using fem::Vector;

// The same force with its tangent withheld, to show what the tangent buys.
class WithoutTangent : public fem::ForceContribution {
 public:
  explicit WithoutTangent(std::shared_ptr<const fem::ForceContribution> inner)
      : inner_(std::move(inner)) {}
  std::string name() const override { return inner_->name() + " (no tangent)"; }
  void add(const Vector& u, double load_factor, Vector& force,
           fem::SymmetricMatrix*) const override {
    inner_->add(u, load_factor, force, nullptr);
  }

 private:
  std::shared_ptr<const fem::ForceContribution> inner_;
};

struct RunResult {
  bool all_converged = true;
  int max_iterations = 0;
  int total_iterations = 0;
  Vec3 tip_displacement = Vec3::Zero();
  double initial_length = 0.0, final_length = 0.0;
};

// 30 x 15 x 15 mm block, 4 x 2 x 2 elements: node (i, j, k) = i + 5 (j + 3 k).
RunResult run(bool with_tangent, double max_force, int steps) {
  fem::Mesh mesh = fem::make_box(Vec3::Zero(), Vec3(0.03, 0.015, 0.015), 4, 2, 2);
  std::vector<fem::PrescribedDof> clamped;
  for (int n : mesh.node_set("x_min")) {
    for (int c = 0; c < 3; ++c) clamped.push_back({n, c, 0.0});
  }
  Fibre top;
  for (int i = 0; i <= 4; ++i) top.nodes.push_back(i + 5 * (2 + 3 * 1));  // j = 2 (top), k = 1
  Muscle m;
  m.name = "SL";
  m.fibres = {top};
  m.max_force = max_force;
  const std::vector<Muscle> muscles = {m};
  const auto solid = std::make_shared<fem::SolidModel>(
      std::move(mesh), fem::make_material("mooney_rivlin5", {{"poisson_ratio", 0.49}}),
      fem::Formulation::mean_dilatation, 1000.0, clamped, fibre_node_pairs(muscles));
  const auto forces = std::make_shared<MuscleForces>(solid, muscles);
  forces->set_activation(0, 1.0);

  fem::MechanicalSystem system(solid);
  if (with_tangent) {
    system.add_load(forces);
  } else {
    system.add_load(std::make_shared<WithoutTangent>(forces));
  }
  fem::DynamicSettings settings;
  settings.damping.stiffness_coefficient = 0.028;  // s, the paper's Rayleigh beta
  fem::NewmarkIntegrator integrator(system, settings);
  const Vector zero = Vector::Zero(solid->num_dofs());
  integrator.initialize(zero, zero);

  RunResult result;
  result.initial_length = forces->muscle_lengths(zero)[0];
  for (int n = 0; n < steps; ++n) {
    const fem::StepReport report = integrator.step(1e-3);
    result.all_converged = result.all_converged && report.converged && report.cuts == 0;
    result.max_iterations = std::max(result.max_iterations, report.iterations);
    result.total_iterations += report.iterations;
  }
  const Vector& u = integrator.displacement();
  result.tip_displacement = u.segment<3>(3 * top.nodes.back());
  result.final_length = forces->muscle_lengths(u)[0];
  return result;
}

TEST(MuscleDynamics, ActivatedTopFibrePullsTheFreeEndTowardTheClampAndCurlsTheBlockUp) {
  const double max_force = 0.05;  // N: ~0.2 kPa over the 15 x 15 mm section, mu0 ~ 4.9 kPa
  const int steps = 60;           // 60 ms, 1 ms steps
  const RunResult r = run(true, max_force, steps);
  const RunResult plain = run(false, max_force, steps);
  std::printf("  tip displacement (%.3f, %.3f, %.3f) mm; fibre %.3f -> %.3f mm\n",
              r.tip_displacement.x() * 1e3, r.tip_displacement.y() * 1e3,
              r.tip_displacement.z() * 1e3, r.initial_length * 1e3, r.final_length * 1e3);
  std::printf(
      "  Newton iterations per step: max %d, mean %.2f with the fibre tangent; "
      "max %d, mean %.2f without\n",
      r.max_iterations, double(r.total_iterations) / steps, plain.max_iterations,
      double(plain.total_iterations) / steps);
  EXPECT_TRUE(r.all_converged);
  EXPECT_LE(r.max_iterations, 4);
  EXPECT_LE(r.total_iterations, plain.total_iterations);
  EXPECT_LT(r.tip_displacement.x(), -1e-4);           // toward the clamp, by more than 0.1 mm
  EXPECT_GT(r.tip_displacement.y(), 0.0);             // the shortened top curls the block up
  EXPECT_LT(std::abs(r.tip_displacement.z()), 1e-9);  // symmetric about the mid plane k = 1
  EXPECT_LT(r.final_length, r.initial_length);
}

}  // namespace
}  // namespace tongue::model
