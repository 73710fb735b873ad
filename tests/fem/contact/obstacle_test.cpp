// Closest point, signed distance and normal of obstacles with exact counterparts: a tilted plane
// (exact to round-off) and a sphere (within the facets' distance from the sphere), the
// consistent second derivative of phi^2 / 2 by finite differences, the smooth normals against
// the plane's and the sphere's, and the checks that refuse a surface that is not one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "fem/contact/obstacle.hpp"
#include "surfaces.hpp"

namespace tongue::fem {
namespace {

TEST(Obstacle, TiltedPlaneGivesTheExactSignedDistance) {
  const Vec3 c(0.01, -0.02, 0.03), n = Vec3(0.3, -0.4, 0.85).normalized();
  const Obstacle plane("plane", test::square(c, n, 0.05, 4));
  EXPECT_FALSE(plane.closed());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  for (int k = 0; k < 200; ++k) {
    const Vec3 foot = c + 0.045 * (u(rng) * e1 + u(rng) * e2);  // inside the square
    const double phi = 0.01 * u(rng);
    const SurfacePoint s = plane.closest(foot + phi * n);
    ASSERT_TRUE(s.valid);
    // Round-off of a 0.05 m geometry: ~1e-17 m per operation, a few dozen operations.
    EXPECT_NEAR(s.distance, phi, 1e-15);
    EXPECT_LT((s.point - foot).norm(), 1e-15);
    EXPECT_LT((s.normal - n).norm(), 1e-14);
  }
  // Beyond the rim of an open sheet a point is neither in front of it nor behind it; its
  // distance is to the rim, signed by the side of the sheet's plane it is on.
  const SurfacePoint behind = plane.closest(c + 0.06 * e1 - 0.001 * n);
  EXPECT_FALSE(behind.valid);
  EXPECT_NEAR(behind.distance, -std::hypot(0.01, 0.001), 1e-15);
  const SurfacePoint in_front = plane.closest(c + 0.06 * e1 + 0.002 * n);
  EXPECT_FALSE(in_front.valid);
  EXPECT_NEAR(in_front.distance, std::hypot(0.01, 0.002), 1e-15);
}

TEST(Obstacle, SphereDistanceIsWithinTheFacetError) {
  const Vec3 c(0.002, 0.001, -0.003);
  const double R = 0.02;
  const Obstacle sphere("sphere", test::icosphere(c, R, 4));
  EXPECT_TRUE(sphere.closed());
  // The facets lie between the sphere and the smallest distance of a facet's plane from c: the
  // polyhedron's distance differs from the sphere's by at most R - that distance.
  double inner = R;
  for (const auto& t : sphere.surface().triangles) {
    const auto& V = sphere.surface().vertices;
    const Vec3 normal = (V[t[1]] - V[t[0]]).cross(V[t[2]] - V[t[0]]).normalized();
    inner = std::min(inner, (V[t[0]] - c).dot(normal));
  }
  const double facet_error = R - inner;
  ASSERT_LT(facet_error, 1e-4);  // level 4: 5120 triangles, sagitta ~ h^2 / 8 R
  std::mt19937 rng(5);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> radius(0.3 * R, 1.7 * R);
  for (int k = 0; k < 500; ++k) {
    const Vec3 direction = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const double r = radius(rng);
    const SurfacePoint s = sphere.closest(c + r * direction);
    ASSERT_TRUE(s.valid);
    EXPECT_LE(std::abs(s.distance - (r - R)), facet_error * (1.0 + 1e-9));
    // The normal turns by at most a facet's angular size (~1/40 rad at level 4) from radial.
    if (std::abs(r - R) > 2.0 * facet_error) {
      EXPECT_GT(s.normal.dot(direction), 0.99);
    }
  }
}

// grad(phi^2 / 2) = phi n and its Jacobian n n^T + curvature, by central differences at points
// whose closest features are faces, edges and vertices of a coarse closed surface, inside and out.
TEST(Obstacle, CurvatureIsTheDerivativeOfTheNormal) {
  const Obstacle sphere("sphere", test::icosphere(Vec3::Zero(), 0.02, 0));
  std::mt19937 rng(11);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> radius(0.012, 0.03);
  const double h = 1e-7;  // m: truncation ~h^2 |phi'''| ~ 1e-14 / 1e-2; round-off ~1e-17 / h
  int checked = 0;
  for (int k = 0; k < 300; ++k) {
    const Vec3 x = radius(rng) * Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const SurfacePoint s = sphere.closest(x);
    const Mat3 hessian = s.normal * s.normal.transpose() + s.curvature;
    Mat3 fd;
    bool smooth = true;  // all six points in the same feature region (no kink in between)
    for (int j = 0; j < 3; ++j) {
      const SurfacePoint p = sphere.closest(x + h * Vec3::Unit(j));
      const SurfacePoint m = sphere.closest(x - h * Vec3::Unit(j));
      smooth = smooth && (p.curvature - s.curvature).norm() < 1e-3 &&
               (m.curvature - s.curvature).norm() < 1e-3 && p.triangle == m.triangle;
      fd.col(j) = (p.distance * p.normal - m.distance * m.normal) / (2.0 * h);
    }
    if (!smooth) continue;
    ++checked;
    // 1e-6: the difference quotient's round-off, 1e-17 m / 1e-7 m, with a margin of 1e4 for
    // the closest point's own round-off in the tree.
    EXPECT_LT((fd - hessian).norm(), 1e-6) << "at " << x.transpose();
  }
  EXPECT_GT(checked, 200);  // most points lie away from a feature's border
}

// On a plane every vertex normal is the plane's: the smooth normals are the faceted ones.
TEST(Obstacle, SmoothNormalsOfAPlaneAreItsNormal) {
  const Vec3 c(0.01, -0.02, 0.03), n = Vec3(0.3, -0.4, 0.85).normalized();
  const Obstacle faceted("plane", test::square(c, n, 0.05, 4));
  const Obstacle smooth("plane", test::square(c, n, 0.05, 4), Normals::smooth);
  EXPECT_EQ(smooth.normals(), Normals::smooth);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  for (int k = 0; k < 200; ++k) {
    const Vec3 x = c + 0.045 * (u(rng) * e1 + u(rng) * e2) + 0.01 * u(rng) * n;
    const SurfacePoint f = faceted.closest(x), s = smooth.closest(x);
    ASSERT_TRUE(s.valid);
    // Round-off of the interpolation: a few dozen operations on unit vectors.
    EXPECT_LT((s.normal - n).norm(), 1e-14);
    EXPECT_NEAR(s.gap, f.distance, 1e-15);
    EXPECT_EQ(s.distance, f.distance);
    EXPECT_EQ(s.curvature, Mat3::Zero());
  }
}

// On a coarse sphere (80 facets, 0.36 rad between neighbours) the interpolated vertex normals
// stand closer to the sphere's own normal (radial) than the facets' normals do.
TEST(Obstacle, SmoothNormalsFollowTheSampledSphere) {
  const Vec3 c(0.002, 0.001, -0.003);
  const double R = 0.02;
  const Obstacle faceted("sphere", test::icosphere(c, R, 1));
  const Obstacle smooth("sphere", test::icosphere(c, R, 1), Normals::smooth);
  std::mt19937 rng(11);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> radius(0.95 * R, 1.05 * R);
  double faceted_error = 0.0, smooth_error = 0.0, worst_smooth = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 direction = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Vec3 x = c + radius(rng) * direction;
    const SurfacePoint f = faceted.closest(x), s = smooth.closest(x);
    ASSERT_TRUE(s.valid);
    EXPECT_EQ(s.distance, f.distance);
    // The sphere's own normal at its closest point to x.
    const Vec3 radial = (x - c).normalized();
    faceted_error += std::acos(std::min(1.0, f.normal.dot(radial)));
    const double angle = std::acos(std::min(1.0, s.normal.dot(radial)));
    smooth_error += angle;
    worst_smooth = std::max(worst_smooth, angle);
  }
  // Measured: a mean of 0.0067 rad smooth against 0.158 rad faceted (about the facet's angular
  // size over two), 0.021 rad at most. Bounds: a twentieth of the faceted mean, a tenth of the
  // angle between neighbouring facets.
  EXPECT_LT(smooth_error, 0.05 * faceted_error);
  EXPECT_LT(worst_smooth, 0.036);
}

// Just inside a coarse sphere the faceted normal jumps where the closest point passes from one
// facet to the next; the smooth one turns continuously: along a path of 10 um steps under the
// surface it turns by at most a step over the sphere's radius, times a margin for the
// interpolation's uneven pace (the facets' own normals turn 0.36 rad over about 9 mm).
TEST(Obstacle, SmoothNormalTurnsContinuouslyUnderTheSurface) {
  const double R = 0.02, step = 1e-5;
  const Obstacle faceted("sphere", test::icosphere(Vec3::Zero(), R, 1));
  const Obstacle smooth("sphere", test::icosphere(Vec3::Zero(), R, 1), Normals::smooth);
  const Vec3 a = Vec3(0.3, 0.5, 0.8).normalized(), b = a.unitOrthogonal();
  double faceted_jump = 0.0, smooth_turn = 0.0;
  SurfacePoint f0 = faceted.closest(0.97 * R * a), s0 = smooth.closest(0.97 * R * a);
  for (int k = 1; k <= 2000; ++k) {  // 20 mm of arc: several facets
    const double angle = k * step / (0.97 * R);
    const Vec3 x = 0.97 * R * (std::cos(angle) * a + std::sin(angle) * b);
    const SurfacePoint f = faceted.closest(x), s = smooth.closest(x);
    faceted_jump = std::max(faceted_jump, (f.normal - f0.normal).norm());
    smooth_turn = std::max(smooth_turn, (s.normal - s0.normal).norm());
    f0 = f;
    s0 = s;
  }
  // Measured: 0.39 faceted (a jump by the angle between facets), 9e-4 smooth (1.8 step / R).
  EXPECT_GT(faceted_jump, 0.1);
  EXPECT_LT(smooth_turn, 5.0 * step / R);
}

// A hint, near or far, changes only how much of the tree a query visits.
TEST(Obstacle, HintDoesNotChangeTheClosestPoint) {
  const Obstacle sphere("sphere", test::icosphere(Vec3(0.001, 0.0, -0.002), 0.02, 3));
  const int triangles = static_cast<int>(sphere.surface().triangles.size());
  std::mt19937 rng(13);
  std::normal_distribution<double> gauss;
  std::uniform_int_distribution<int> any(0, triangles - 1);
  for (int k = 0; k < 300; ++k) {
    const Vec3 x = 0.02 * Vec3(gauss(rng), gauss(rng), gauss(rng));
    const SurfacePoint plain = sphere.closest(x);
    const SurfacePoint near = sphere.closest(x + Vec3(1e-5, 0.0, 0.0));  // the last iterate's
    const int far = any(rng);
    const Vec3 far_point = sphere.surface().vertices[sphere.surface().triangles[far][0]];
    for (const SurfacePoint& s :
         {sphere.closest(x, near.triangle, near.point), sphere.closest(x, far, far_point)}) {
      EXPECT_EQ(s.distance, plain.distance);
      EXPECT_EQ(s.point, plain.point);
      EXPECT_EQ(s.normal, plain.normal);
    }
  }
}

// The triangles listed within |c - closest point| + 2 r of c hold the closest point of every x
// within r of c, and the nearest of them with its margin to the next is what a search of every
// triangle gives.
TEST(Obstacle, NearTrianglesHoldTheClosestPoint) {
  const Obstacle sphere("sphere", test::icosphere(Vec3(0.001, 0.0, -0.002), 0.02, 2));
  const auto& surface = sphere.surface();
  std::vector<int> all(surface.triangles.size());
  for (std::size_t t = 0; t < all.size(); ++t) all[t] = static_cast<int>(t);
  std::mt19937 rng(17);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> within(-1.0, 1.0);
  const double r = 0.002;  // m, a fifth of a facet's size: the nearest triangle changes within it
  std::size_t largest = 0;
  for (int k = 0; k < 100; ++k) {
    const Vec3 c = 0.021 * Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const std::vector<int> near =
        sphere.triangles_near(c, (c - sphere.closest(c).point).norm() + 2.0 * r);
    largest = std::max(largest, near.size());
    for (int j = 0; j < 20; ++j) {
      Vec3 d(within(rng), within(rng), within(rng));
      const Vec3 x = c + r * d / std::max(1.0, d.norm());
      const SurfacePoint tree = sphere.closest(x);
      const Obstacle::Nearest listed = sphere.nearest_among(x, near);
      const Obstacle::Nearest every = sphere.nearest_among(x, all);
      // The same nearest distance: the closest point of each triangle is computed alike;
      // ties between triangles sharing an edge may pick either, with the same point.
      EXPECT_EQ(listed.distance, every.distance);
      EXPECT_LT((sphere.closest_on(x, listed.triangle).point - tree.point).norm(), 1e-15);
      EXPECT_NEAR(listed.distance, (x - tree.point).norm(), 1e-15);
      EXPECT_LE(listed.next, every.next + 1e-15);  // the list may lack the next of all
      EXPECT_GE(listed.next, listed.distance);
    }
  }
  EXPECT_LT(largest, surface.triangles.size() / 4);  // the lists are local
}

TEST(Obstacle, RefusesWhatIsNotASurface) {
  const auto message = [](TriangleSurface s) {
    try {
      Obstacle o("bad", std::move(s));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  TriangleSurface s = test::square(Vec3::Zero(), Vec3::UnitZ(), 0.01);
  TriangleSurface empty = s;
  empty.triangles.clear();
  EXPECT_NE(message(empty).find("no triangles"), std::string::npos);
  TriangleSurface out_of_range = s;
  out_of_range.triangles[1][2] = 7;
  EXPECT_NE(message(out_of_range).find("out of"), std::string::npos);
  TriangleSurface degenerate = s;
  degenerate.vertices.push_back(0.5 * (s.vertices[0] + s.vertices[1]));
  degenerate.triangles.push_back({0, 1, 4});
  EXPECT_NE(message(degenerate).find("degenerate"), std::string::npos);
  TriangleSurface flipped = s;
  std::swap(flipped.triangles[1][0], flipped.triangles[1][1]);
  EXPECT_NE(message(flipped).find("oriented oppositely"), std::string::npos);
  TriangleSurface fan = s;
  fan.vertices.push_back(Vec3(0, 0, 0.01));
  fan.triangles.push_back({0, 3, 4});
  EXPECT_NE(message(fan).find("share"), std::string::npos);
  TriangleSurface inside_out = test::icosphere(Vec3::Zero(), 0.01, 1);
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  EXPECT_NE(message(inside_out).find("inward normals"), std::string::npos);
  EXPECT_EQ(message(test::icosphere(Vec3::Zero(), 0.01, 1)), "accepted");
}

}  // namespace
}  // namespace tongue::fem
