// The built-in tongue in the built-in vocal tract, through its scenes: free at rest under
// gravity; pushed by GGp against the hard palate (/i/), by SG against the velum (/k/) and by
// SL, GGa and GGp against the alveolar ridge (/t/), every step converges and no node penetrates
// an obstacle deeper than the bound the penalty is chosen for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run.hpp"
#include "support/run_command.hpp"

namespace tongue::scene_run {
namespace {

// The largest penetration the default contact settings allow [m]: the penalty's at the scenes'
// resting forces, the multipliers' tolerance on impact (fem::ContactSettings).
constexpr double kPenetrationBound = 1e-4;

struct ContactRun {
  std::vector<double> depth;  // m, the deepest penetration of each step
  int augmentations = 0;      // solves repeated with the multipliers
  double deepest() const {    // m, over the run
    return depth.empty() ? 0.0 : *std::max_element(depth.begin(), depth.end());
  }
  fem::ContactReport last;  // at its end
  std::vector<std::string> obstacles;
  fem::Mesh mesh;  // the rest positions and the landmarks' node sets
};

ContactRun run_scene(const scene::Scene& scene) {
  const std::string& name = scene.source;
  SceneRun run(scene, scene::build_scene(scene));
  const fem::StaticReport settled = run.start();
  EXPECT_TRUE(settled.converged) << settled.message;
  const fem::RigidContact& contact = *run.built().contact;
  ContactRun out;
  for (const auto& o : contact.obstacles()) out.obstacles.push_back(o->name());
  out.mesh = run.built().solid->mesh();
  // At rest under gravity the tongue touches nothing.
  EXPECT_TRUE(contact.report(run.displacement()).contacts.empty()) << name;
  const int steps = scene::time_step_count(scene.analysis);
  for (int s = 0; s < steps; ++s) {
    const double dt = scene::time_step_length(scene.analysis, s);
    const StepResult r = run.step(dt, run.built().activations.levels_at(run.time() + dt));
    EXPECT_TRUE(r.report.converged) << name << " step " << s + 1 << ": " << r.report.message;
    if (!r.report.converged) break;
    out.augmentations += r.report.augmentations;
    out.last = contact.report(run.displacement());
    out.depth.push_back(out.last.max_penetration);
  }
  return out;
}

ContactRun run_scene(const std::string& name) {
  return run_scene(scene::read_scene("../../scenes/" + name + ".yaml"));
}

int obstacle(const ContactRun& r, const std::string& name) {
  return static_cast<int>(std::find(r.obstacles.begin(), r.obstacles.end(), name) -
                          r.obstacles.begin());
}

TEST(TongueInVocalTract, GgpPressesTheDorsumOnTheHardPalate) {
  const ContactRun r = run_scene("tongue_i");
  EXPECT_LT(r.deepest(), kPenetrationBound);
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
  EXPECT_LT(r.deepest(), kPenetrationBound);
  const fem::Vec3 f = r.last.obstacle_force.at(obstacle(r, "velum"));
  EXPECT_GT(f.norm(), 0.1);  // 0.37 N measured
  EXPECT_GT(f.y(), 0.0);     // the dorsum pushes the velum up
}

// The hardest push the scenes' muscles can give: GGp and SG at full force (level 1) from rest into
// the vocal tract (scenes/tongue_i.yaml's scene with its activations replaced). Every step
// converges (an inverted element would stop it) and no node is ever deeper than the bound: the
// first strike, at the speed the full force gives the tongue (about 0.8 m/s), went 0.142 mm deep
// on the penalty alone, and the step that made it is solved again with the augmented
// Lagrangian's multipliers (0.084 mm deep at most over the run, measured).
TEST(TongueInVocalTract, FullGgpAndSgConvergeAndStayWithinTheBound) {
  std::string text = tongue::testing::read_text("../../scenes/tongue_i.yaml");
  const std::string six = "  - {group: GGp, force: 6.0, start: 0.0}";
  ASSERT_NE(text.find(six), std::string::npos);
  text.replace(text.find(six), six.size(),
               "  - {group: GGp, level: 1.0, start: 0.0}\n  - {group: SG, level: 1.0, start: 0.0}");
  const ContactRun r = run_scene(scene::parse_scene(text, "../../scenes", "full GGp + SG"));
  ASSERT_EQ(r.depth.size(), 50u);
  // Pushed on at full force, the tongue stays on the palate once it has struck it: the alpha
  // method damps the contact springs' stiff modes, with which the average-acceleration rule
  // threw the dorsum back off the palate (no node in contact at 24 ms) to strike it again.
  const auto strike = std::find_if(r.depth.begin(), r.depth.end(), [](double d) { return d > 0; });
  ASSERT_NE(strike, r.depth.end());
  for (auto d = strike; d != r.depth.end(); ++d)
    EXPECT_GT(*d, 0.0) << "step " << (d - r.depth.begin()) + 1 << " out of contact";
  for (std::size_t s = 0; s < r.depth.size(); ++s)
    EXPECT_LE(r.depth[s], kPenetrationBound) << "step " << s + 1;
  EXPECT_GT(r.augmentations, 0);  // the strike needed them
  EXPECT_GT(r.last.obstacle_force.at(obstacle(r, "hard_palate")).norm(), 3.0);  // 5.0 N measured
}

// The first node of a landmark's node set.
int landmark(const ContactRun& r, const std::string& name) {
  return r.mesh.node_sets.at(name).front();
}

TEST(TongueInVocalTract, SlGgaAndGgpCloseTheTipOnTheAlveolarRidge) {
  const ContactRun r = run_scene("tongue_t");
  EXPECT_LT(r.deepest(), kPenetrationBound);
  // The ridge carries the push (1.49 N measured), forward on it.
  const fem::Vec3 f = r.last.obstacle_force.at(obstacle(r, "hard_palate"));
  EXPECT_GT(f.norm(), 0.5);
  EXPECT_GT(f.x(), 0.0);
  // The tip is in contact, and over the middle 60 % of the width nothing behind the blade is:
  // the dorsum stays off the palate (the front two rows of the EPG close; behind them only the
  // lateral margins touch, on the teeth and the palate's sides).
  const int tip = landmark(r, "tip");
  const double blade_x = r.mesh.nodes.at(landmark(r, "blade")).x();
  double half_width = 0.0;
  for (const fem::Vec3& x : r.mesh.nodes) half_width = std::max(half_width, std::abs(x.z()));
  bool tip_touches = false;
  for (const fem::NodeContact& c : r.last.contacts) {
    tip_touches |= c.node == tip;
    const fem::Vec3& x = r.mesh.nodes.at(c.node);
    if (std::abs(x.z()) < 0.6 * half_width) {
      EXPECT_GT(x.x(), blade_x) << "node " << c.node << " touches behind the blade";
    }
  }
  EXPECT_TRUE(tip_touches);
}

}  // namespace
}  // namespace tongue::scene_run
