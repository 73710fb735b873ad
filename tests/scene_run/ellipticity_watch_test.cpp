// EllipticityWatch: the findings of first_loss called in the caller's thread, each delivered by
// the next call, whatever the worker's timing; collect() gives the last state's. With
// check_every(n) only every n-th step's state is checked, and the last one handed over.
#include "scene_run/ellipticity_watch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::scene_run {
namespace {

using fem::Vec3;
using fem::Vector;

// A 120 mm bar of 12 elements along x, each stretched to 1.3 (screened in, still elliptic)
// except those from x = end on, stretched to `tip` (mooney_rivlin5 loses ellipticity beyond a
// uniaxial stretch of about 1.54). Isochoric: the lateral stretches are 1 / sqrt(stretch).
Vector bar(const fem::Mesh& mesh, double end, double tip) {
  Vector u(3 * mesh.num_nodes());
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const Vec3 X = mesh.nodes[n];
    const bool out = X.x() > end;
    const double x = out ? 1.3 * end + tip * (X.x() - end) : 1.3 * X.x();
    const double lateral = 1.0 / std::sqrt(out ? tip : 1.3);
    u.segment<3>(3 * n) = Vec3(x, lateral * X.y(), lateral * X.z()) - X;
  }
  return u;
}

struct Bar {
  fem::Mesh mesh = fem::make_box(Vec3::Zero(), Vec3(0.12, 0.01, 0.01), 12, 1, 1);
  fem::SolidModel solid{mesh,
                        fem::make_material("mooney_rivlin5", {}),
                        fem::Formulation::mean_dilatation,
                        1000.0,
                        {}};
  // States 1..n: elliptic at first, then the last element (from step 5 on) and the last three
  // (from step 9 on) stretched to 1.8.
  std::vector<Vector> states() const {
    std::vector<Vector> s;
    for (int step = 1; step <= 14; ++step)
      s.push_back(step < 5 ? bar(mesh, 0.12, 1.0) : bar(mesh, step < 9 ? 0.11 : 0.09, 1.8));
    return s;
  }
};

// The states handed to the watch as steps 1, 2, ... 4 ms apart: the one finding and the step
// whose call returned it.
struct Reported {
  std::optional<EllipticityFinding> finding;
  int by = 0;
};
Reported hand_over(EllipticityWatch& watch, const std::vector<Vector>& states) {
  Reported r;
  for (std::size_t k = 0; k < states.size(); ++k) {
    const int step = static_cast<int>(k) + 1;
    if (auto f = watch.check(states[k], step, 0.004 * step)) {
      EXPECT_FALSE(r.finding) << "one finding per watch";
      r.finding = f;
      r.by = step;
    }
  }
  return r;
}

TEST(EllipticityWatch, ReportsFirstLossOfEachStateWithTheNextCall) {
  const Bar b;
  const std::vector<Vector> states = b.states();
  // The reference: first_loss in this thread, state by state.
  fem::EllipticityMonitor monitor(b.solid);
  std::optional<int> found_at;
  std::optional<fem::EllipticityLoss> expected;
  for (std::size_t k = 0; k < states.size(); ++k) {
    if (auto loss = monitor.first_loss(states[k])) {
      ASSERT_FALSE(found_at) << "first_loss reports once";
      found_at = static_cast<int>(k) + 1;
      expected = loss;
    }
  }
  ASSERT_TRUE(found_at) << "the bar should lose ellipticity";
  ASSERT_GE(*found_at, 5);

  EllipticityWatch watch(b.solid);
  const auto [finding, reported_by] = hand_over(watch, states);
  EXPECT_FALSE(watch.collect());  // the finding came with a check, not left over
  ASSERT_TRUE(finding);
  EXPECT_EQ(finding->step, *found_at);
  EXPECT_EQ(reported_by, *found_at + 1);  // one step late, always
  EXPECT_DOUBLE_EQ(finding->time, 0.004 * *found_at);
  EXPECT_EQ(finding->loss.element, expected->element);
  EXPECT_EQ(finding->loss.min_eigenvalue, expected->min_eigenvalue);  // the same computation
  EXPECT_NE(finding->warning.find("no longer strongly elliptic"), std::string::npos);
}

TEST(EllipticityWatch, CollectGivesTheLastStatesFinding) {
  const Bar b;
  const fem::Mesh& mesh = b.mesh;
  EllipticityWatch watch(b.solid);
  // Every element stretched beyond the limit (end before the bar: x = 1.8 X plus a
  // translation): the first check finds it.
  const Vector stretched = bar(mesh, -0.01, 1.8);
  EXPECT_FALSE(watch.check(stretched, 1, 0.002));
  const std::optional<EllipticityFinding> f = watch.collect();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->step, 1);
  EXPECT_FALSE(watch.collect());  // taken once
  EXPECT_FALSE(watch.check(stretched, 2, 0.004));
  EXPECT_FALSE(watch.collect());  // reported once per watch
}

// A restarted run reports its loss again, at the step the first run did; a finding of the state
// before the restart is still delivered by the next call.
TEST(EllipticityWatch, RearmedItReportsTheNextRunsLossAtTheSameStep) {
  const Bar b;
  const std::vector<Vector> states = b.states();
  EllipticityWatch watch(b.solid);
  const std::optional<EllipticityFinding> first = hand_over(watch, states).finding;
  ASSERT_TRUE(first);
  watch.rearm();
  const std::optional<EllipticityFinding> again = hand_over(watch, states).finding;
  ASSERT_TRUE(again);
  EXPECT_EQ(again->step, first->step);
  EXPECT_EQ(again->loss.element, first->loss.element);

  // Stretched beyond the limit in the last state before the rearm: the next call delivers it.
  watch.rearm();
  EXPECT_FALSE(watch.check(bar(b.mesh, -0.01, 1.8), 7, 0.028));
  watch.rearm();
  const std::optional<EllipticityFinding> left = watch.check(bar(b.mesh, 0.12, 1.0), 1, 0.004);
  ASSERT_TRUE(left);
  EXPECT_EQ(left->step, 7);
}

// The bar loses ellipticity in state 5 (ReportsFirstLossOfEachStateWithTheNextCall); checking
// every fourth state, the watch finds it in state 8 and reports it with step 12's call, the
// calls between returning nothing and waiting for nothing.
TEST(EllipticityWatch, CheckingEveryFourthStateFindsTheLossAtTheNextOne) {
  const Bar b;
  const std::vector<Vector> states = b.states();
  EllipticityWatch watch(b.solid);
  watch.check_every(4);
  const auto [finding, reported_by] = hand_over(watch, states);
  ASSERT_TRUE(finding);
  EXPECT_EQ(finding->step, 8);
  EXPECT_DOUBLE_EQ(finding->time, 0.032);
  EXPECT_EQ(reported_by, 12);
  EXPECT_FALSE(watch.collect());  // state 14, unchecked by its call, adds nothing after a loss
  EXPECT_THROW(watch.check_every(0), std::invalid_argument);
}

// A loss in a state that check_every left unchecked, the last one handed over, is found by
// collect(), or, after a rearm, delivered by the next call.
TEST(EllipticityWatch, CollectChecksTheLastStateCheckEveryLeft) {
  const Bar b;
  const Vector elliptic = bar(b.mesh, 0.12, 1.0), lost = bar(b.mesh, -0.01, 1.8);
  EllipticityWatch watch(b.solid);
  watch.check_every(4);
  for (int step = 1; step <= 6; ++step) EXPECT_FALSE(watch.check(elliptic, step, 0.004 * step));
  EXPECT_FALSE(watch.check(lost, 7, 0.028));
  const std::optional<EllipticityFinding> f = watch.collect();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->step, 7);
  EXPECT_FALSE(watch.collect());  // taken once

  watch.rearm();
  EXPECT_FALSE(watch.check(lost, 3, 0.012));
  watch.rearm();
  const std::optional<EllipticityFinding> left = watch.check(elliptic, 4, 0.016);
  ASSERT_TRUE(left);
  EXPECT_EQ(left->step, 3);
}

TEST(EllipticityWatch, AnEllipticRunReportsNothing) {
  const Bar b;
  EllipticityWatch watch(b.solid);
  for (int step = 1; step <= 20; ++step)
    EXPECT_FALSE(watch.check(bar(b.mesh, 0.12, 1.0), step, 0.002 * step));
  EXPECT_FALSE(watch.collect());
}

}  // namespace
}  // namespace tongue::scene_run
