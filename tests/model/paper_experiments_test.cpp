// The simulations of Gerard et al. 2003 (sec. IV.2): from static equilibrium under gravity, a
// 120 ms step of muscle force, mooney_rivlin5 at nu = 0.49, Rayleigh beta = 0.028 s, active
// muscle tissue stiffening up to 110 / 15 and the fibre segments' active force-length relation
// (both as in the tongue scenes). Each test
// checks the directions the paper reports on the landmarks. Thresholds are set well below the
// displacements the model gives (printed), so that they test the direction, not the digits:
// 0.1 mm is an order of magnitude above the solver's tolerance on positions and below every
// reported displacement.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "fem/integrator/newmark_integrator.hpp"
#include "fem/integrator/static_solver.hpp"
#include "fem/material/material_factory.hpp"
#include "model/active_stiffening.hpp"
#include "model/default_tongue.hpp"
#include "model/muscle_forces.hpp"

namespace tongue::model {
namespace {

using Displacements = std::map<std::string, fem::Vec3>;  // landmark -> displacement [m]

class PaperExperiments : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tongue_ = new TongueModel(make_default_tongue());
    solid_ = new std::shared_ptr<fem::SolidModel>(std::make_shared<fem::SolidModel>(
        tongue_->mesh, fem::make_material("mooney_rivlin5", {{"poisson_ratio", 0.49}}),
        fem::Formulation::mean_dilatation, 1000.0, tongue_boundary_conditions(tongue_->mesh),
        fibre_node_pairs(tongue_->muscles)));
  }
  static void TearDownTestSuite() {
    delete solid_;
    delete tongue_;
  }

  // Runs `group` at `force` newtons (both halves together) for 120 ms from rest under gravity;
  // returns the landmark displacements from the rest state, after checking the run.
  static Displacements run(const std::string& group, double force) {
    const auto& solid = *solid_;
    fem::MechanicalSystem system(solid);
    system.add_load(
        std::make_shared<fem::ConstantForce>("gravity", solid->body_force({0, -9.81, 0})));
    auto muscles = std::make_shared<MuscleForces>(solid, tongue_->muscles);
    system.add_load(muscles);
    system.add_load(std::make_shared<ActiveStiffening>(solid, muscles));  // as the tongue scenes

    fem::Vector rest = fem::Vector::Zero(solid->num_dofs());
    const fem::StaticReport settle = fem::solve_static(system, rest, fem::StaticSettings{});
    EXPECT_TRUE(settle.converged) << settle.message;

    double group_max = 0.0;
    for (int m = 0; m < muscles->num_muscles(); ++m)
      if (in_group(tongue_->muscles[m].name, group)) group_max += tongue_->muscles[m].max_force;
    for (int m = 0; m < muscles->num_muscles(); ++m) {
      if (group == "all")
        muscles->set_activation(m, 1.0);
      else if (in_group(tongue_->muscles[m].name, group))
        muscles->set_activation(m, force / group_max);
    }

    fem::DynamicSettings settings;
    settings.damping.stiffness_coefficient = 0.028;
    fem::NewmarkIntegrator integrator(system, settings);
    integrator.initialize(rest, fem::Vector::Zero(rest.size()));
    const double dt = 0.004;  // s; 30 steps over the 120 ms of the paper
    for (int step = 0; step < 30; ++step) {
      const fem::StepReport r = integrator.step(dt);
      EXPECT_TRUE(r.converged) << group << ": " << r.message;
      if (!r.converged) break;
    }
    const fem::Vector& u = integrator.displacement();
    fem::Vector f;
    const fem::AssemblyStatus status = solid->assemble(u, f, nullptr);
    EXPECT_TRUE(status.ok) << "inverted element " << status.inverted_element;
    const double volume_change = solid->current_volume(u) / solid->reference_volume() - 1.0;
    EXPECT_LT(std::abs(volume_change), 0.02);  // the paper's bound at nu = 0.49

    Displacements d;
    char what[64];
    if (group == "all") {
      std::snprintf(what, sizeof what, "all muscles at full activation");
    } else {
      std::snprintf(what, sizeof what, "%s %.1f N", group.c_str(), force);
    }
    std::printf(
        "%s for 120 ms (volume change %+.3f %%, min det F %.3f), landmark displacements "
        "[mm]:\n",
        what, volume_change * 100, status.min_J);
    for (const std::string& name : landmark_names()) {
      const int n = tongue_->mesh.node_set(name).front();
      d[name] = (u - rest).segment<3>(3 * n);
      std::printf("  %-15s dx %+7.3f  dy %+7.3f  dz %+7.3f\n", name.c_str(), d[name].x() * 1e3,
                  d[name].y() * 1e3, d[name].z() * 1e3);
    }
    return d;
  }

  static bool in_group(const std::string& muscle, const std::string& group) {
    return muscle == group || muscle.rfind(group + "_", 0) == 0;
  }

  static TongueModel* tongue_;
  static std::shared_ptr<fem::SolidModel>* solid_;
};
TongueModel* PaperExperiments::tongue_ = nullptr;
std::shared_ptr<fem::SolidModel>* PaperExperiments::solid_ = nullptr;

constexpr double kMin = 1e-4;  // m: the smallest displacement taken as a direction

TEST_F(PaperExperiments, StyloglossusRaisesTheVelarDorsumMovesTheBodyBackLowersTheTip) {
  const Displacements d = run("SG", 3.0);
  EXPECT_GT(d.at("velar_dorsum").y(), 10 * kMin);  // the dorsum rises in the velar region
  EXPECT_LT(d.at("palatal_dorsum").x(), -kMin);    // the body moves back ...
  EXPECT_LT(d.at("velar_dorsum").x(), -kMin);
  EXPECT_GT(d.at("velar_dorsum").x(), -0.005);  // ... slightly (less than 5 mm)
  EXPECT_LT(d.at("tip").y(), -0.5 * kMin);      // the tip lowers
}

TEST_F(PaperExperiments, PosteriorGenioglossusMovesTheBackForwardAndTheUpperPartUp) {
  const Displacements d = run("GGp", 4.0);
  EXPECT_GT(d.at("root").x(), 10 * kMin);        // the back of the tongue moves forward
  EXPECT_GT(d.at("palatal_dorsum").x(), kMin);   // the body moves forward too
  EXPECT_GT(d.at("palatal_dorsum").y(), kMin);   // the upper part rises slightly
  EXPECT_GT(d.at("root").x(), d.at("tip").x());  // the back moves most
}

TEST_F(PaperExperiments, SuperiorLongitudinalRetractsAndRaisesTheTip) {
  const Displacements d = run("SL", 1.0);
  EXPECT_LT(d.at("tip").x(), -10 * kMin);  // the tip retracts
  EXPECT_GT(d.at("tip").y(), 10 * kMin);   // and rises
}

TEST_F(PaperExperiments, AllMusclesAtMaximumForceCompleteWithoutInversion) {
  // Every muscle at full activation for 120 ms: 293 N in all. run() checks that every step
  // converges, no element is inverted and the volume changes by less than 2 %.
  run("all", 0.0);
}

}  // namespace
}  // namespace tongue::model
