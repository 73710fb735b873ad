// The built-in tongue in the built-in vocal tract, through its scenes: free at rest under
// gravity; pushed by GGp against the hard palate (/i/) and by SG against the velum (/k/), every
// step converges and no node penetrates an obstacle deeper than the bound the penalty is chosen
// for.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run.hpp"

namespace tongue::scene_run {
namespace {

// The largest penetration the default penalty allows the scenes [m] (fem::ContactSettings).
constexpr double kPenetrationBound = 1e-4;

struct ContactRun {
  double deepest = 0.0;     // m, over the run
  fem::ContactReport last;  // at its end
  std::vector<std::string> obstacles;
};

ContactRun run_scene(const std::string& name) {
  const scene::Scene scene = scene::read_scene("../../scenes/" + name + ".yaml");
  SceneRun run(scene, scene::build_scene(scene));
  const fem::StaticReport settled = run.start();
  EXPECT_TRUE(settled.converged) << settled.message;
  const fem::RigidContact& contact = *run.built().contact;
  ContactRun out;
  for (const auto& o : contact.obstacles()) out.obstacles.push_back(o->name());
  // At rest under gravity the tongue touches nothing.
  EXPECT_TRUE(contact.report(run.displacement()).contacts.empty()) << name;
  const int steps = scene::time_step_count(scene.analysis);
  for (int s = 0; s < steps; ++s) {
    const double dt = scene::time_step_length(scene.analysis, s);
    const StepResult r = run.step(dt, run.built().activations.levels_at(run.time() + dt));
    EXPECT_TRUE(r.report.converged) << name << " step " << s + 1 << ": " << r.report.message;
    if (!r.report.converged) break;
    out.last = contact.report(run.displacement());
    out.deepest = std::max(out.deepest, out.last.max_penetration);
  }
  return out;
}

int obstacle(const ContactRun& r, const std::string& name) {
  return static_cast<int>(std::find(r.obstacles.begin(), r.obstacles.end(), name) -
                          r.obstacles.begin());
}

TEST(TongueInVocalTract, GgpPressesTheDorsumOnTheHardPalate) {
  const ContactRun r = run_scene("tongue_i");
  EXPECT_LT(r.deepest, kPenetrationBound);
  // The palate carries the push: more than 1 N at the end (1.8 N measured), upward and forward
  // on the palate (the tongue pushes it that way), the sides in balance by symmetry.
  const fem::Vec3 f = r.last.obstacle_force.at(obstacle(r, "hard_palate"));
  EXPECT_GT(f.norm(), 1.0);
  EXPECT_GT(f.x(), 0.0);
  EXPECT_LT(std::abs(f.z()), 0.02 * f.norm());  // the error of the accepted steps, ~10 um x eps
  for (const fem::NodeContact& c : r.last.contacts)
    EXPECT_EQ(r.obstacles.at(c.obstacle), "hard_palate") << "node " << c.node;
}

TEST(TongueInVocalTract, StyloglossusClosesOnTheVelum) {
  const ContactRun r = run_scene("tongue_k");
  EXPECT_LT(r.deepest, kPenetrationBound);
  const fem::Vec3 f = r.last.obstacle_force.at(obstacle(r, "velum"));
  EXPECT_GT(f.norm(), 0.1);  // 0.37 N measured
  EXPECT_GT(f.y(), 0.0);     // the dorsum pushes the velum up
}

}  // namespace
}  // namespace tongue::scene_run
