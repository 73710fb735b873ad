// Fibre forces (Payan & Perrier 1997): f = -T dL/dx checked by finite differences of the length
// on strongly curved fibres, the closed-form cases (straight fibre, right-angle corner), the
// totals (internal without origin, T toward the attachment with one), inactive muscles, and the
// length and lengthening-velocity outputs. With the active force-length relation: each segment
// pulls with its own tension T f(l / l_rest), and a segment passing through zero length pulls
// with no force at all (where constant tension jumps by 2 T).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "model/muscle_forces.hpp"
#include "model/muscle_test_support.hpp"
#include "support/finite_difference.hpp"

namespace tongue::model {
namespace {

using fem::Vec3;
using fem::Vector;
using testing::fibre;
using testing::grid_box;
using testing::grid_node;
using testing::make_solid;
using testing::muscle;

Vec3 node_force(const Vector& f, int node) {
  return f.segment<3>(3 * node);
}

Vec3 total(const Vector& f) {
  Vec3 t = Vec3::Zero();
  for (Eigen::Index n = 0; n < f.size() / 3; ++n) t += f.segment<3>(3 * n);
  return t;
}

// Displacement that puts the given nodes at the given positions and moves every other node by
// a random few tenths of a millimetre.
Vector displacement_to(const fem::SolidModel& solid, const std::vector<int>& nodes,
                       const std::vector<Vec3>& positions, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-3e-4, 3e-4);
  Vector u(solid.num_dofs());
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = jitter(rng);
  for (size_t i = 0; i < nodes.size(); ++i) {
    u.segment<3>(3 * nodes[i]) = positions[i] - solid.rest_positions().segment<3>(3 * nodes[i]);
  }
  return u;
}

// Strongly curved polylines: fibre nodes on a helix of radius 8 mm turning 100 degrees per
// segment (each inner node sees a 100-degree turn), and a zigzag with 150-degree turns.
struct CurvedScene {
  std::vector<Muscle> muscles;
  std::shared_ptr<const fem::SolidModel> solid;
  Vector u;

  CurvedScene() {
    const std::vector<int> helix = {grid_node(0, 0, 0), grid_node(2, 1, 0), grid_node(4, 2, 1),
                                    grid_node(1, 2, 2), grid_node(3, 0, 2)};
    const std::vector<int> zigzag = {grid_node(0, 2, 0), grid_node(1, 1, 1), grid_node(2, 2, 0),
                                     grid_node(3, 1, 1)};
    const std::vector<int> short_one = {grid_node(4, 0, 0), grid_node(4, 1, 0)};
    Fibre with_origin = fibre(helix, 1.0);
    with_origin.origin = Vec3(-0.01, -0.005, 0.004);
    muscles = {muscle("SG", {with_origin}, 24.0),
               muscle("HG", {fibre(zigzag, 0.25), fibre(short_one, 0.75)}, 65.0)};
    solid = make_solid(grid_box(), muscles);

    std::vector<int> nodes;
    std::vector<Vec3> x;
    for (size_t i = 0; i < helix.size(); ++i) {
      const double angle = i * 100.0 * M_PI / 180.0;
      nodes.push_back(helix[i]);
      x.emplace_back(0.02 + 0.008 * std::cos(angle), 0.01 + 0.008 * std::sin(angle),
                     0.002 + 0.003 * i);
    }
    // Zigzag: consecutive segments 10 mm long turning by 150 degrees (30-degree inner angles).
    Vec3 p(0.005, 0.005, 0.005);
    for (size_t i = 0; i < zigzag.size(); ++i) {
      nodes.push_back(zigzag[i]);
      x.push_back(p);
      const double angle = (i % 2 == 0 ? 75.0 : -75.0) * M_PI / 180.0;
      p += 0.01 * Vec3(std::cos(angle), std::sin(angle), 0.0);
    }
    u = displacement_to(*solid, nodes, x, 7);
  }
};

// Lengths of a fibre's segments at positions x (3 n), the one from its origin first [m].
std::vector<double> segment_lengths(const Fibre& fibre, const Vector& x) {
  std::vector<double> out;
  Vec3 from = fibre.origin ? *fibre.origin : Vec3(x.segment<3>(3 * fibre.nodes[0]));
  for (size_t i = fibre.origin ? 0 : 1; i < fibre.nodes.size(); ++i) {
    const Vec3 to = x.segment<3>(3 * fibre.nodes[i]);
    out.push_back((to - from).norm());
    from = to;
  }
  return out;
}

TEST(MuscleForces, ForceIsMinusTensionTimesTheLengthGradient) {
  CurvedScene scene;
  MuscleForces muscles(scene.solid, scene.muscles, ActiveForceLength::constant_tension());
  const Vector a = (Vector(2) << 0.6, 0.3).finished();
  muscles.set_activations(a);
  const double load_factor = 0.7;
  Vector f = Vector::Zero(scene.solid->num_dofs());
  muscles.add(scene.u, load_factor, f, nullptr);

  // Each muscle's length is the weighted mean of its fibre lengths, and its fibres' tensions are
  // a F_max w, so f = -sum_m a_m F_max,m grad(muscle length m), scaled by the load factor.
  // Central differences with h = 1e-7 m: truncation ~ (h / l)^2 ~ 1e-10 relative for segments
  // of l >= 5 mm, round-off ~ eps L / h ~ 1e-10 m / m; the bound leaves two decades.
  const Eigen::MatrixXd dL = tongue::testing::central_difference_jacobian(
      [&](const Vector& u) { return muscles.muscle_lengths(u); }, scene.u, 1e-7);
  const Vector expected = -load_factor * dL.transpose() * muscles.muscle_forces();
  const double error = (f - expected).norm() / expected.norm();
  std::printf("  force vs -T grad L: relative error %.2e\n", error);
  EXPECT_LT(error, 1e-8);
  // The nodes of no fibre carry no force.
  EXPECT_EQ(node_force(f, grid_node(0, 1, 1)).norm(), 0.0);
}

TEST(MuscleForces, WithForceLengthEachSegmentPullsWithItsOwnTension) {
  CurvedScene scene;
  const ActiveForceLength relation;
  MuscleForces muscles(scene.solid, scene.muscles, relation);
  const Vector a = (Vector(2) << 0.6, 0.3).finished();
  muscles.set_activations(a);
  const double load_factor = 0.7;
  Vector f = Vector::Zero(scene.solid->num_dofs());
  muscles.add(scene.u, load_factor, f, nullptr);

  // f = -sum over segments of t_s grad l_s with t_s = load_factor a F_max w f(l_s / l_rest,s):
  // the gradient of sum c_s l_s(u), c_s = t_s frozen at scene.u, by central differences (as in
  // the test above).
  const Vector rest = scene.solid->rest_positions(), x0 = rest + scene.u;
  std::vector<double> c;
  int on_the_limb = 0;  // segments between the zero-force length and rest: f strictly in (0, 1)
  for (size_t m = 0; m < scene.muscles.size(); ++m) {
    for (const Fibre& fibre : scene.muscles[m].fibres) {
      const std::vector<double> l = segment_lengths(fibre, x0),
                                l_rest = segment_lengths(fibre, rest);
      for (size_t s = 0; s < l.size(); ++s) {
        const double scale = relation.value(l[s] / l_rest[s]);
        on_the_limb += scale > 0.0 && scale < 1.0;
        c.push_back(load_factor * a[m] * scene.muscles[m].max_force * fibre.weight * scale);
      }
    }
  }
  ASSERT_GE(on_the_limb, 3) << "the scene should exercise the ascending limb";
  const auto weighted_length = [&](const Vector& u) -> Vector {
    double sum = 0.0;
    size_t k = 0;
    for (const Muscle& muscle : scene.muscles)
      for (const Fibre& fibre : muscle.fibres)
        for (double l : segment_lengths(fibre, rest + u)) sum += c[k++] * l;
    return Vector::Constant(1, sum);
  };
  const Vector expected =
      -tongue::testing::central_difference_jacobian(weighted_length, scene.u, 1e-7).transpose();
  const double error = (f - expected).norm() / expected.norm();
  std::printf(
      "  force vs -sum t_s grad l_s (%d segments on the ascending limb): relative error "
      "%.2e\n",
      on_the_limb, error);
  EXPECT_LT(error, 1e-8);
}

TEST(MuscleForces, SegmentShortenedToThreeQuartersPullsWithElevenSixteenthsOfTheTension) {
  // One 10 mm segment along x, its end moved 2.5 mm back: lambda = 3/4, f = 11/16 (by hand,
  // force_length_test.cpp).
  const std::vector<Muscle> list = {
      muscle("IL", {fibre({grid_node(1, 1, 1), grid_node(2, 1, 1)})}, 9.0)};
  MuscleForces muscles(make_solid(grid_box(), list), list);
  muscles.set_activation(0, 1.0);
  Vector u = Vector::Zero(3 * 45), f = Vector::Zero(3 * 45);
  u[3 * grid_node(2, 1, 1)] = -0.0025;
  muscles.add(u, 1.0, f, nullptr);
  // One unit vector and one product: a few roundings of 9 N.
  EXPECT_LT((node_force(f, grid_node(2, 1, 1)) - Vec3(-9.0 * 11.0 / 16.0, 0, 0)).norm(), 1e-14);
  EXPECT_LT((node_force(f, grid_node(1, 1, 1)) - Vec3(9.0 * 11.0 / 16.0, 0, 0)).norm(), 1e-14);
}

// The failure this relation removes: two consecutive fibre nodes crushed together by the
// segment's own tension. With constant tension the force on a node jumps by 2 T as the segment
// passes through zero length (its direction flips), which Newton cannot converge across; with
// the force-length relation the segment pulls with nothing below half its rest length, so the
// force is continuous (zero) there.
TEST(MuscleForces, SegmentPassingThroughZeroLengthPullsWithNoForce) {
  const int a = grid_node(1, 1, 1), b = grid_node(2, 1, 1);
  const std::vector<Muscle> list = {muscle("MH", {fibre({a, b})}, 39.0)};
  const auto solid = make_solid(grid_box(), list);
  MuscleForces hill(solid, list), constant(solid, list, ActiveForceLength::constant_tension());
  hill.set_activation(0, 1.0);
  constant.set_activation(0, 1.0);
  const auto force_on_b = [&](const MuscleForces& muscles, double offset) {
    // b at a + offset along x (rest: offset 10 mm).
    Vector u = Vector::Zero(3 * 45), f = Vector::Zero(3 * 45);
    u[3 * b] = offset - 0.01;
    fem::SymmetricMatrix K(solid->pattern());
    muscles.add(u, 1.0, f, &K);
    for (double v : K.values()) EXPECT_TRUE(std::isfinite(v)) << "offset " << offset;
    return Vec3(node_force(f, b));
  };
  for (const double offset : {-1e-4, -1e-9, 0.0, 1e-9, 1e-4, 0.004, 0.0049}) {
    EXPECT_EQ(force_on_b(hill, offset), Vec3::Zero()) << "offset " << offset << " m";
  }
  EXPECT_GT(force_on_b(hill, 0.0051).norm(), 0.0);  // just above half the rest length
  // Constant tension: 39 N toward a from either side.
  EXPECT_EQ(force_on_b(constant, -1e-9).x(), 39.0);
  EXPECT_EQ(force_on_b(constant, 1e-9).x(), -39.0);
}

TEST(MuscleForces, StraightFibrePullsItsEndsTogetherAndLeavesInnerNodesFree) {
  const std::vector<int> line = {grid_node(0, 0, 0), grid_node(1, 0, 0), grid_node(2, 0, 0),
                                 grid_node(3, 0, 0), grid_node(4, 0, 0)};
  const std::vector<Muscle> list = {muscle("SL", {fibre(line)}, 19.0)};
  MuscleForces muscles(make_solid(grid_box(), list), list);
  muscles.set_activation(0, 0.5);
  const double T = 0.5 * 19.0;
  Vector f = Vector::Zero(3 * 45);
  muscles.add(Vector::Zero(3 * 45), 1.0, f, nullptr);
  // Unit vectors of 10 mm segments along x are exact up to one rounding: 1e-15 T.
  EXPECT_LT((node_force(f, line.front()) - Vec3(T, 0, 0)).norm(), 1e-14 * T);
  EXPECT_LT((node_force(f, line.back()) - Vec3(-T, 0, 0)).norm(), 1e-14 * T);
  for (size_t i = 1; i + 1 < line.size(); ++i) {
    EXPECT_LT(node_force(f, line[i]).norm(), 1e-14 * T) << "inner node " << line[i];
  }
}

TEST(MuscleForces, RightAngleCornerFeelsSqrt2TimesTheTension) {
  // (0, 0, 0) -> (10, 0, 0) -> (10, 10, 0) mm: the corner is pulled toward both neighbours.
  const std::vector<int> corner = {grid_node(0, 0, 0), grid_node(1, 0, 0), grid_node(1, 1, 0)};
  const std::vector<Muscle> list = {muscle("T", {fibre(corner)}, 50.0)};
  MuscleForces muscles(make_solid(grid_box(), list), list);
  muscles.set_activation(0, 0.2);
  const double T = 0.2 * 50.0;
  Vector f = Vector::Zero(3 * 45);
  muscles.add(Vector::Zero(3 * 45), 1.0, f, nullptr);
  const Vec3 e_prev(-1, 0, 0), e_next(0, 1, 0);
  EXPECT_LT((node_force(f, corner[1]) - T * (e_prev + e_next)).norm(), 1e-14 * T);
  EXPECT_NEAR(node_force(f, corner[1]).norm(), std::sqrt(2.0) * T, 1e-14 * T);
  EXPECT_LT((node_force(f, corner[0]) - Vec3(T, 0, 0)).norm(), 1e-14 * T);
  EXPECT_LT((node_force(f, corner[2]) - Vec3(0, -T, 0)).norm(), 1e-14 * T);
}

TEST(MuscleForces, FibreWithoutOriginIsInternalWithOriginPullsTowardIt) {
  CurvedScene scene;
  MuscleForces muscles(scene.solid, scene.muscles);
  const Vector x = scene.solid->rest_positions() + scene.u;

  // HG (no origin): the forces are internal and sum to zero; ~10 terms of size T: 1e-14 T.
  muscles.set_activations((Vector(2) << 0.0, 1.0).finished());
  Vector f = Vector::Zero(scene.solid->num_dofs());
  muscles.add(scene.u, 1.0, f, nullptr);
  EXPECT_LT(total(f).norm(), 1e-14 * 65.0);

  // SG (origin P): the fibre's net pull is T toward P from its first node.
  muscles.set_activations((Vector(2) << 1.0, 0.0).finished());
  f.setZero();
  muscles.add(scene.u, 1.0, f, nullptr);
  const Fibre& sg = scene.muscles[0].fibres[0];
  const Vec3 to_origin = (*sg.origin - x.segment<3>(3 * sg.nodes[0])).normalized();
  EXPECT_LT((total(f) - 24.0 * to_origin).norm(), 1e-14 * 24.0);
}

TEST(MuscleForces, InactiveMusclesAddNothing) {
  CurvedScene scene;
  MuscleForces muscles(scene.solid, scene.muscles);
  Vector f = Vector::Constant(scene.solid->num_dofs(), 0.125);
  const Vector before = f;
  fem::SymmetricMatrix K(scene.solid->pattern());
  muscles.add(scene.u, 1.0, f, &K);
  EXPECT_EQ(f, before);
  for (double v : K.values()) ASSERT_EQ(v, 0.0);

  // Back to zero after having been active; also a zero load factor.
  muscles.set_activation(1, 0.4);
  muscles.add(scene.u, 0.0, f, &K);
  muscles.set_activation(1, 0.0);
  muscles.add(scene.u, 1.0, f, &K);
  EXPECT_EQ(f, before);
  for (double v : K.values()) ASSERT_EQ(v, 0.0);
}

TEST(MuscleForces, TotalTensionIsActivationTimesMaxForce) {
  CurvedScene scene;
  MuscleForces muscles(scene.solid, scene.muscles);
  muscles.set_activation(muscles.index_of("HG"), 0.5);
  EXPECT_EQ(muscles.index_of("GGa"), -1);
  const Vector t = muscles.muscle_forces();
  EXPECT_EQ(t[0], 0.0);
  EXPECT_EQ(t[1], 32.5);
}

TEST(MuscleLengths, AreWeightedMeansOfFibreLengths) {
  // Fibres of 40 mm (along x) and 20 mm (along y) with weights 1/4, 3/4; one of 10 mm plus a
  // 5 mm segment from its origin.
  const std::vector<int> along_x = {grid_node(0, 0, 0), grid_node(1, 0, 0), grid_node(2, 0, 0),
                                    grid_node(3, 0, 0), grid_node(4, 0, 0)};
  const std::vector<int> along_y = {grid_node(0, 0, 2), grid_node(0, 1, 2), grid_node(0, 2, 2)};
  Fibre attached = fibre({grid_node(2, 2, 2), grid_node(3, 2, 2)});
  attached.origin = Vec3(0.02, 0.025, 0.02);
  const std::vector<Muscle> list = {muscle("IL", {fibre(along_x, 0.25), fibre(along_y, 0.75)}, 9),
                                    muscle("GGa", {attached}, 18)};
  MuscleForces muscles(make_solid(grid_box(), list), list);
  const Vector L = muscles.muscle_lengths(Vector::Zero(3 * 45));
  EXPECT_NEAR(L[0], 0.25 * 0.04 + 0.75 * 0.02, 1e-15);
  EXPECT_NEAR(L[1], 0.015, 1e-15);
}

TEST(MuscleVelocities, MatchTimeDerivativesOfTheLengthsAlongAMotion) {
  CurvedScene scene;
  MuscleForces muscles(scene.solid, scene.muscles);
  // u(t) = u0 + sin(w t) U1 + t^2 U2: a smooth motion with known velocity.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-2e-3, 2e-3);
  const Eigen::Index n = scene.solid->num_dofs();
  Vector U1(n), U2(n);
  for (Eigen::Index i = 0; i < n; ++i) U1[i] = d(rng), U2[i] = 10.0 * d(rng);
  const double w = 2.0 * M_PI * 5.0;  // rad/s
  const auto u_at = [&](double t) -> Vector { return scene.u + std::sin(w * t) * U1 + t * t * U2; };
  const auto v_at = [&](double t) -> Vector { return w * std::cos(w * t) * U1 + 2.0 * t * U2; };
  double worst = 0.0;
  for (double t : {0.0, 0.013, 0.05, 0.11}) {
    // Central differences in time, h = 1e-6 s: truncation h^2 L''' / 6 with L''' ~ |v|^3 / l^2
    // ~ 10 m/s^3 (|v| ~ 0.06 m/s, l ~ 5 mm) is ~2e-12 m/s; round-off eps L / h ~ 1e-11 m/s;
    // both ~1e-10 relative to rates of ~0.05 m/s; the bound leaves room for times at which a
    // rate happens to be small.
    const double h = 1e-6;
    const Vector fd =
        (muscles.muscle_lengths(u_at(t + h)) - muscles.muscle_lengths(u_at(t - h))) / (2.0 * h);
    Vector lengths, rates;
    muscles.muscle_kinematics(u_at(t), v_at(t), lengths, rates);
    EXPECT_EQ(lengths, muscles.muscle_lengths(u_at(t)));  // the same sums in the same order
    const double error = (rates - fd).norm() / fd.norm();
    worst = std::max(worst, error);
    EXPECT_LT(error, 1e-7) << "t = " << t;
  }
  std::printf("  velocities vs time differences of lengths: worst relative error %.2e\n", worst);
}

TEST(MuscleForces, ActivationLevelsOutsideZeroOneAreRejected) {
  CurvedScene scene;
  MuscleForces muscles(scene.solid, scene.muscles);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double level : {-0.01, 1.0 + 1e-12, nan, inf, -inf}) {
    EXPECT_THROW(muscles.set_activation(0, level), std::invalid_argument) << level;
  }
  EXPECT_THROW(muscles.set_activation(2, 0.5), std::invalid_argument);
  EXPECT_THROW(muscles.set_activation(-1, 0.5), std::invalid_argument);
  EXPECT_THROW(muscles.set_activations(Vector::Zero(3)), std::invalid_argument);
  // A rejected vector changes nothing.
  muscles.set_activations((Vector(2) << 0.0, 1.0).finished());
  EXPECT_THROW(muscles.set_activations((Vector(2) << 0.5, 1.5).finished()), std::invalid_argument);
  EXPECT_EQ(muscles.activations(), (Vector(2) << 0.0, 1.0).finished());
  try {
    muscles.set_activation(1, 2.0);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'HG'"), std::string::npos) << e.what();
  }
}

TEST(MuscleForces, ConstructionChecksTheMusclesAgainstTheSolid) {
  const std::vector<int> far_apart = {grid_node(0, 0, 0), grid_node(4, 2, 2)};
  std::vector<Muscle> list = {muscle("MH", {fibre(far_apart)}, 39.0)};
  // Without the fibre pairs the pattern cannot hold the fibre stiffness.
  const auto plain = std::make_shared<fem::SolidModel>(
      grid_box(), fem::make_material("neo_hookean", {{"shear_modulus", 5e3}}),
      fem::Formulation::standard, 1000.0, std::vector<fem::PrescribedDof>{});
  EXPECT_THROW(MuscleForces(plain, list), std::invalid_argument);
  EXPECT_NO_THROW(MuscleForces(make_solid(grid_box(), list), list));
  // A node outside the mesh, two muscles of one name, an origin on its first node.
  const auto solid = make_solid(grid_box(), list);
  list[0].fibres[0].nodes[1] = 45;
  EXPECT_THROW(MuscleForces(solid, list), std::invalid_argument);
  list[0].fibres[0].nodes[1] = grid_node(4, 2, 2);
  EXPECT_THROW(MuscleForces(solid, {list[0], list[0]}), std::invalid_argument);
  Fibre on_node = fibre({grid_node(1, 1, 1)});
  on_node.origin = Vec3(0.01, 0.01, 0.01);
  EXPECT_THROW(MuscleForces(solid, {muscle("V", {on_node}, 20.0)}), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::model
