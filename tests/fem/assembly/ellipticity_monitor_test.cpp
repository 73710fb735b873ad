// EllipticityMonitor: its screen is safe (no law of the project loses ellipticity within it),
// and on a mesh under a homogeneous deformation it reports exactly what the material-level
// check says for that deformation.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <string>

#include "fem/assembly/ellipticity_monitor.hpp"
#include "fem/material/ellipticity.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::fem {
namespace {

Mat3 uniaxial(double stretch) {
  return Vec3(stretch, 1.0 / std::sqrt(stretch), 1.0 / std::sqrt(stretch)).asDiagonal();
}

// The box's nodes displaced by the homogeneous deformation F about the origin.
Vector homogeneous(const Mesh& mesh, const Mat3& F) {
  Vector u(3 * mesh.num_nodes());
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    u.segment<3>(3 * n) = (F - Mat3::Identity()) * mesh.nodes[n];
  }
  return u;
}

// The laws' parameters where the factory has no default (a tongue-like stiffness).
std::map<std::string, double> parameters(const std::string& type) {
  std::map<std::string, double> p{{"poisson_ratio", 0.49}};
  if (type == "neo_hookean") p["shear_modulus"] = 5000.0;  // Pa
  if (type == "linear") p["youngs_modulus"] = 15e3;        // Pa
  return p;
}

// Random isochoric deformations with ||C_bar - I|| up to the screen: every material is still
// strongly elliptic, so skipping those elements cannot hide a loss.
TEST(EllipticityMonitor, ScreenedStrainsAreEllipticForEveryMaterial) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> entry(-0.6, 0.6);
  for (const std::string& type : material_types()) {
    const auto m = make_material(type, parameters(type));
    int tried = 0;
    while (tried < 500) {
      Mat3 F = Mat3::Identity();
      for (int i = 0; i < 9; ++i) F(i % 3, i / 3) += entry(random);
      if (F.determinant() <= 0.1) continue;
      F /= std::cbrt(F.determinant());
      const Mat3 C = F.transpose() * F;
      if ((C - Mat3::Identity()).norm() > EllipticityMonitor::kDefaultScreen) continue;
      ++tried;
      EXPECT_TRUE(check_ellipticity(*m, F).elliptic()) << type << "\n" << F;
    }
  }
}

TEST(EllipticityMonitor, ReportsTheLossWhereTheMaterialLosesIt) {
  const Mesh mesh = make_box(Vec3::Zero(), Vec3(0.03, 0.01, 0.01), 3, 1, 1);
  const std::shared_ptr<const Material> mr5 = make_material("mooney_rivlin5", {});
  const SolidModel solid(mesh, mr5, Formulation::mean_dilatation, 1000.0, {});
  const EllipticityMonitor monitor(solid);
  EXPECT_FALSE(monitor.check(Vector::Zero(3 * mesh.num_nodes())));
  EXPECT_FALSE(monitor.check(homogeneous(mesh, uniaxial(1.3))));

  const auto loss = monitor.check(homogeneous(mesh, uniaxial(1.8)));
  ASSERT_TRUE(loss);
  EXPECT_GE(loss->element, 0);
  // Every element has the same F, so the same smallest eigenvalue as the material-level check
  // (round-off of F from nodal coordinates: ~1e-15 relative).
  EXPECT_NEAR(loss->min_eigenvalue, check_ellipticity(*mr5, uniaxial(1.8)).min_eigenvalue,
              1e-8 * mr5->initial_shear_modulus());

  const SolidModel neo(mesh, make_material("neo_hookean", parameters("neo_hookean")),
                       Formulation::mean_dilatation, 1000.0, {});
  EXPECT_FALSE(EllipticityMonitor(neo).check(homogeneous(mesh, uniaxial(1.8))));
}

// A 12-element bar along x (12 cm) stretched isochorically to 1.45 (|C_bar - I| = 1.19: beyond
// the screen, still elliptic), but element `odd`, stretched to `stretch`.
Vector stretched_bar(const Mesh& mesh, int odd, double stretch) {
  Vector u(3 * mesh.num_nodes());
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const Vec3 X = mesh.nodes[n];
    const double start = 0.01 * odd, end = start + 0.01;  // m: the odd element's ends
    const double before = std::min(X.x(), start), inside = std::clamp(X.x(), start, end) - start;
    const double after = std::max(X.x(), end) - end;
    const double x = 1.45 * (before + after) + stretch * inside;
    const double lateral = 1.0 / std::sqrt(X.x() > start && X.x() <= end ? stretch : 1.45);
    u.segment<3>(3 * n) = Vec3(x, lateral * X.y(), lateral * X.z()) - X;
  }
  return u;
}

// first_loss searches a few of the elements screened in per call, those strained most beyond the
// screen first: of twelve elements beyond it, the one stretched beyond the limit is found at the
// first call, and reported once.
TEST(EllipticityMonitor, FirstLossSearchesTheMostStrainedFirstAndReportsOnce) {
  const Mesh mesh = make_box(Vec3::Zero(), Vec3(0.12, 0.01, 0.01), 12, 1, 1);
  const SolidModel solid(mesh, make_material("mooney_rivlin5", {}), Formulation::mean_dilatation,
                         1000.0, {});
  EllipticityMonitor monitor(solid);
  const Vector u = stretched_bar(mesh, 11, 1.8);
  int calls = 0;
  std::optional<EllipticityLoss> loss;
  while (!loss && calls < 10) {
    loss = monitor.first_loss(u);
    ++calls;
  }
  ASSERT_TRUE(loss);
  EXPECT_EQ(loss->element, 11);
  EXPECT_EQ(calls, 1);
  EXPECT_FALSE(monitor.first_loss(u));  // reported once
}

// An element already searched is searched again, before those not yet searched, when its strain
// grows: the first call searches elements 0-3 of the bar, all elliptic; then element 0 is
// stretched beyond the limit and the next call finds it.
TEST(EllipticityMonitor, AnElementSearchedIsSearchedAgainWhenItsStrainGrows) {
  const Mesh mesh = make_box(Vec3::Zero(), Vec3(0.12, 0.01, 0.01), 12, 1, 1);
  const SolidModel solid(mesh, make_material("mooney_rivlin5", {}), Formulation::mean_dilatation,
                         1000.0, {});
  EllipticityMonitor monitor(solid);
  EXPECT_FALSE(monitor.first_loss(stretched_bar(mesh, 0, 1.45)));
  const auto loss = monitor.first_loss(stretched_bar(mesh, 0, 1.8));
  ASSERT_TRUE(loss);
  EXPECT_EQ(loss->element, 0);
}

}  // namespace
}  // namespace tongue::fem
