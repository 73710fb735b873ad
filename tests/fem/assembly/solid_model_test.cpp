// SolidModel: the assembled tangent is the derivative of the assembled internal force, which is
// the derivative of the strain energy (central finite differences on a distorted box at a
// strongly deformed, non-homogeneous state); mass, volume and inversion reporting.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "fem/assembly/solid_model.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"
#include "support/finite_difference.hpp"
#include "support/reference_hex8_element.hpp"

namespace tongue::fem {
namespace {

using testing::central_difference_jacobian;

constexpr double kLx = 0.03, kLy = 0.02, kLz = 0.02;  // m
constexpr double kDensity = 1040.0;                   // kg/m^3

// A box of nx x ny x nz elements (10 mm ones by default) with every interior node moved by up to
// ~1.5 mm, so that no two elements share their geometry.
Mesh distorted_box(int nx = 3, int ny = 2, int nz = 2) {
  return map_nodes(make_box(Vec3::Zero(), Vec3(kLx, kLy, kLz), nx, ny, nz), [](const Vec3& X) {
    const Vec3 s(X.x() / kLx, X.y() / kLy, X.z() / kLz);  // in [0, 1]
    const double bump = std::sin(M_PI * s.x()) * std::sin(M_PI * s.y()) * std::sin(M_PI * s.z());
    return Vec3(X.x() + 1.5e-3 * bump + 0.5e-3 * s.y() * s.z(), X.y() - 1.0e-3 * bump * s.x(),
                X.z() + 0.8e-3 * std::sin(M_PI * s.x()) * s.y());
  });
}

// Large rotation, stretch and shear plus bending and twist: F varies strongly over the box.
Vec3 deformation(const Vec3& X) {
  Mat3 F;
  F << 1.3, 0.25, -0.1, 0.05, 0.8, 0.15, -0.1, 0.1, 1.1;
  const Mat3 R = Eigen::AngleAxisd(0.5, Vec3(1, -2, 1).normalized()).toRotationMatrix();
  const double t = X.x() / kLx;
  Vec3 u = (R * F - Mat3::Identity()) * X;
  u.z() += 4e-3 * t * t;                               // bending
  u.y() += 2e-3 * t * std::sin(3.0 * X.z() / kLz);     // twist-like
  u.x() += 1.5e-3 * std::sin(M_PI * X.y() / kLy) * t;  // non-affine stretch
  return u;
}

Vector displacement_field(const Mesh& mesh, const std::function<Vec3(const Vec3&)>& u) {
  Vector v(3 * mesh.num_nodes());
  for (int n = 0; n < mesh.num_nodes(); ++n) v.segment<3>(3 * n) = u(mesh.nodes[n]);
  return v;
}

std::shared_ptr<const Material> mooney_rivlin() {
  return make_material("mooney_rivlin5", {});  // the paper's law, nu = 0.49
}

// x_min clamped at the displacement of the deformed state, plus single components on x_max.
std::vector<PrescribedDof> constraints(const Mesh& mesh) {
  std::vector<PrescribedDof> p;
  for (int n : mesh.node_set("x_min")) {
    const Vec3 u = deformation(mesh.nodes[n]);
    for (int c = 0; c < 3; ++c) p.push_back({n, c, u[c]});
  }
  const std::vector<int>& right = mesh.node_set("x_max");
  for (std::size_t i = 0; i < right.size(); i += 2) {
    p.push_back({right[i], 2, deformation(mesh.nodes[right[i]]).z()});
  }
  return p;
}

class AssembledTangent : public ::testing::TestWithParam<Formulation> {};

TEST_P(AssembledTangent, MatchesFiniteDifferencesOfTheAssembledForce) {
  const Mesh mesh = distorted_box();
  const SolidModel model(mesh, mooney_rivlin(), GetParam(), kDensity, constraints(mesh));
  const DofMap& dofs = model.dofs();
  ASSERT_GT(dofs.num_free(), 60);
  ASSERT_LT(dofs.num_free(), dofs.num_dofs());

  Vector u_full = displacement_field(mesh, deformation);
  // Free dofs at the deformed state; prescribed dofs stay at their prescribed values.
  const Vector y0 = dofs.gather_free(u_full);
  auto full = [&](const Vector& y) {
    Vector u = dofs.prescribed_values();
    dofs.scatter_free(y, u);
    return u;
  };
  ASSERT_LT((full(y0) - u_full).norm(), 1e-15);

  Vector f;
  SymmetricMatrix K(model.pattern());
  double energy = 0.0;
  const AssemblyStatus status = model.assemble(full(y0), f, &K, &energy);
  ASSERT_TRUE(status.ok);
  // Strongly deformed (displacements comparable to the 10 mm elements), nowhere near inversion.
  EXPECT_GT(u_full.lpNorm<Eigen::Infinity>(), 8e-3);
  EXPECT_GT(status.min_J, 0.3);
  EXPECT_GT(energy, 0.0);

  auto force = [&](const Vector& y) {
    Vector fy;
    EXPECT_TRUE(model.assemble(full(y), fy, nullptr).ok);
    return Vector(dofs.gather_free(fy));
  };
  auto strain_energy = [&](const Vector& y) {
    Vector fy;
    double e = 0.0;
    EXPECT_TRUE(model.assemble(full(y), fy, nullptr, &e).ok);
    return Vector::Constant(1, e);
  };
  // h = 1e-8 m against 10 mm elements and displacements of ~10 mm (relative 1e-6): truncation
  // O(h^2 / L^2) ~ 1e-12 and round-off O(eps L / h) ~ 1e-10 of the result, both far below the
  // 1e-6 required, which a wrong sign, factor or misplaced entry in the scatter would exceed by
  // orders of magnitude.
  const double h = 1e-8;
  const Eigen::MatrixXd dK = central_difference_jacobian(force, y0, h);
  const Eigen::MatrixXd K_dense = K.to_dense();
  EXPECT_LT((dK - K_dense).norm() / K_dense.norm(), 1e-6);

  const Vector dE = central_difference_jacobian(strain_energy, y0, h).transpose();
  const Vector f_free = dofs.gather_free(f);
  EXPECT_LT((dE - f_free).norm() / f_free.norm(), 1e-6);
}

INSTANTIATE_TEST_SUITE_P(MooneyRivlin5, AssembledTangent,
                         ::testing::Values(Formulation::standard, Formulation::mean_dilatation),
                         [](const auto& info) {
                           return std::string(info.param == Formulation::standard
                                                  ? "standard"
                                                  : "mean_dilatation");
                         });

struct BatchCase {
  std::string material;
  Formulation formulation;
  double dilation;  // uniform stretch applied on top of the deformation
  // Weights on every third element only (a hyper-reduction sample: evaluated packed into
  // batches of their own) instead of on all but three (evaluated in the mesh's batches).
  bool sample = false;
};

// The elements' weights of a case: some 0 (elements skipped), the others between 1 and 2.
std::vector<double> case_weights(const BatchCase& c, int elements) {
  std::vector<double> weights(elements);
  for (int e = 0; e < elements; ++e) {
    const bool weighted = c.sample ? e % 3 == 0 : e % 29 != 1;
    weights[e] = weighted ? 1.0 + 0.25 * (e % 5) : 0.0;
  }
  return weights;
}

std::string batch_case_name(const ::testing::TestParamInfo<BatchCase>& info) {
  return info.param.material +
         (info.param.formulation == Formulation::standard ? "_standard" : "_mean_dilatation") +
         (info.param.dilation > 1.0 ? "_dilated" : "") + (info.param.sample ? "_sample" : "");
}

class BatchedResidual : public ::testing::TestWithParam<BatchCase> {};

// The residual path evaluates uncoupled materials 8 elements at a time (hex8_batch.hpp). Its
// assembled force, energy and smallest det F are those of the straightforward reference element
// summed element by element: on a 5 x 4 x 3 box (60 elements: 7 full batches and a partial one),
// with element weights of which some are 0 (elements skipped), with and without the I2 terms
// (mooney_rivlin5, neo_hookean), and dilated by 1.5 (det F above 2, where the kernel takes
// std::cbrt instead of its own J^{-1/3}); weights on a sample of the elements are evaluated in
// batches packed of the sample alone.
TEST_P(BatchedResidual, EqualsTheReferenceElementSummedOverTheMesh) {
  const BatchCase c = GetParam();
  const Mesh mesh = distorted_box(5, 4, 3);
  std::map<std::string, double> parameters;
  if (c.material == "neo_hookean") parameters["shear_modulus"] = 3000.0;  // Pa
  const std::shared_ptr<const Material> material = make_material(c.material, parameters);
  const SolidModel model(mesh, material, c.formulation, kDensity, {});
  const Vector u = displacement_field(
      mesh, [&](const Vec3& X) { return Vec3(c.dilation * (X + deformation(X)) - X); });
  const std::vector<double> weights = case_weights(c, mesh.num_elements());

  Vector f = Vector::Zero(model.num_dofs());
  double energy = 0.0;
  const AssemblyStatus status = model.add_weighted(u, weights, f, nullptr, &energy);
  ASSERT_TRUE(status.ok);

  Vector expected = Vector::Zero(model.num_dofs());
  double expected_energy = 0.0, scale = 0.0;
  double expected_min_J = std::numeric_limits<double>::infinity();
  for (int e = 0; e < mesh.num_elements(); ++e) {
    if (weights[e] == 0.0) continue;
    hex8::ElementCoords X, x;
    for (int a = 0; a < 8; ++a) {
      const int n = mesh.elements[e][a];
      X.row(a) = mesh.nodes[n].transpose();
      x.row(a) = (mesh.nodes[n] + u.segment<3>(3 * n)).transpose();
    }
    ElementResponse r;
    ASSERT_TRUE(testing::reference_evaluate_element(make_element_geometry(X), x, *material,
                                                    c.formulation, false, r));
    for (int a = 0; a < 8; ++a)
      expected.segment<3>(3 * mesh.elements[e][a]) += weights[e] * r.force.segment<3>(3 * a);
    expected_energy += weights[e] * r.energy;
    scale += weights[e] * r.force.norm();
    expected_min_J = std::min(expected_min_J, r.min_J);
  }
  if (c.dilation > 1.0) {
    EXPECT_GT(status.min_J, 2.0);
  }
  // The same sums in another order, J^{-1/3} from Newton steps instead of std::cbrt, fused
  // multiply-adds where the CPU has them: round-off, measured 3e-16 of the summed element force
  // norms (energy 3e-16). 1e-13 leaves a wide margin and still fails for a J^{-1/3} off by 1e-12,
  // let alone a wrong term.
  EXPECT_LT((f - expected).norm(), 1e-13 * scale);
  EXPECT_NEAR(energy, expected_energy, 1e-13 * std::abs(expected_energy));
  EXPECT_NEAR(status.min_J, expected_min_J, 1e-14 * expected_min_J);
}

INSTANTIATE_TEST_SUITE_P(
    UncoupledMaterials, BatchedResidual,
    ::testing::Values(BatchCase{"mooney_rivlin5", Formulation::mean_dilatation, 1.0},
                      BatchCase{"mooney_rivlin5", Formulation::standard, 1.0},
                      BatchCase{"mooney_rivlin5", Formulation::mean_dilatation, 1.5},
                      BatchCase{"neo_hookean", Formulation::mean_dilatation, 1.0},
                      BatchCase{"neo_hookean", Formulation::standard, 1.5},
                      BatchCase{"mooney_rivlin5", Formulation::mean_dilatation, 1.0, true},
                      BatchCase{"neo_hookean", Formulation::standard, 1.5, true}),
    batch_case_name);

class BatchedTangent : public ::testing::TestWithParam<BatchCase> {};

// With a stiffness wanted, uncoupled materials go through the tangent kernel 8 elements at a
// time (hex8_batch_tangent.hpp). The assembled tangent, force and energy are those of the
// reference element summed element by element over the free dofs: on a 5 x 4 x 3 box (7 full
// batches and a partial one) with prescribed dofs (entries dropped), element weights of which
// some are 0 (or a sample's, packed), with and without the I2 terms, dilated by 1.5 in one case.
TEST_P(BatchedTangent, EqualsTheReferenceElementAssembled) {
  const BatchCase c = GetParam();
  const Mesh mesh = distorted_box(5, 4, 3);
  std::map<std::string, double> parameters;
  if (c.material == "neo_hookean") parameters["shear_modulus"] = 3000.0;  // Pa
  const std::shared_ptr<const Material> material = make_material(c.material, parameters);
  const SolidModel model(mesh, material, c.formulation, kDensity, constraints(mesh));
  const DofMap& dofs = model.dofs();
  ASSERT_LT(dofs.num_free(), dofs.num_dofs());
  const Vector u = displacement_field(
      mesh, [&](const Vec3& X) { return Vec3(c.dilation * (X + deformation(X)) - X); });
  const std::vector<double> weights = case_weights(c, mesh.num_elements());

  Vector f = Vector::Zero(model.num_dofs());
  SymmetricMatrix K(model.pattern());
  double energy = 0.0;
  const AssemblyStatus status = model.add_weighted(u, weights, f, &K, &energy);
  ASSERT_TRUE(status.ok);

  Vector expected_f = Vector::Zero(model.num_dofs());
  Eigen::MatrixXd expected_K = Eigen::MatrixXd::Zero(dofs.num_free(), dofs.num_free());
  double expected_energy = 0.0, scale = 0.0;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    if (weights[e] == 0.0) continue;
    const Hex8& nodes = mesh.elements[e];
    hex8::ElementCoords X, x;
    for (int a = 0; a < 8; ++a) {
      X.row(a) = mesh.nodes[nodes[a]].transpose();
      x.row(a) = (mesh.nodes[nodes[a]] + u.segment<3>(3 * nodes[a])).transpose();
    }
    ElementResponse r;
    ASSERT_TRUE(testing::reference_evaluate_element(make_element_geometry(X), x, *material,
                                                    c.formulation, true, r));
    for (int i = 0; i < 24; ++i) {
      expected_f[3 * nodes[i / 3] + i % 3] += weights[e] * r.force[i];
      const int fi = dofs.free_index(3 * nodes[i / 3] + i % 3);
      for (int j = 0; j < 24; ++j) {
        const int fj = dofs.free_index(3 * nodes[j / 3] + j % 3);
        if (fi >= 0 && fj >= 0) expected_K(fi, fj) += weights[e] * r.stiffness(i, j);
      }
    }
    expected_energy += weights[e] * r.energy;
    scale += weights[e] * r.force.norm();
  }
  // Element stiffnesses equal to round-off of their largest entry (hex8_element_test), summed in
  // the same order: 1e-12 of the largest entry, as there.
  const Eigen::MatrixXd K_dense = K.to_dense();
  const double largest = expected_K.cwiseAbs().maxCoeff();
  EXPECT_LT((K_dense - expected_K).cwiseAbs().maxCoeff(), 1e-12 * largest);
  // As the residual path (BatchedResidual).
  EXPECT_LT((f - expected_f).norm(), 1e-13 * scale);
  EXPECT_NEAR(energy, expected_energy, 1e-13 * std::abs(expected_energy));
}

INSTANTIATE_TEST_SUITE_P(
    UncoupledMaterials, BatchedTangent,
    ::testing::Values(BatchCase{"mooney_rivlin5", Formulation::mean_dilatation, 1.0},
                      BatchCase{"mooney_rivlin5", Formulation::standard, 1.0},
                      BatchCase{"mooney_rivlin5", Formulation::mean_dilatation, 1.5},
                      BatchCase{"neo_hookean", Formulation::mean_dilatation, 1.0},
                      BatchCase{"exponential", Formulation::standard, 1.5},
                      BatchCase{"mooney_rivlin5", Formulation::mean_dilatation, 1.0, true},
                      BatchCase{"exponential", Formulation::standard, 1.5, true}),
    batch_case_name);

// A sample's elements are packed into batches of their own, kept while the same elements are
// weighted: another sample in between is packed anew, and the first one's force is then the
// same bits as before.
TEST(SolidModel, AnotherSampleIsPackedAnew) {
  const Mesh mesh = distorted_box(5, 4, 3);
  const SolidModel model(mesh, mooney_rivlin(), Formulation::mean_dilatation, kDensity, {});
  const Vector u = displacement_field(mesh, deformation);
  std::vector<double> first(mesh.num_elements(), 0.0), second = first;
  for (int e = 0; e < mesh.num_elements(); e += 4) first[e] = 1.5;
  for (int e = 1; e < mesh.num_elements(); e += 5) second[e] = 0.5;
  auto force = [&](const std::vector<double>& weights) {
    Vector f = Vector::Zero(model.num_dofs());
    EXPECT_TRUE(model.add_weighted(u, weights, f, nullptr).ok);
    return f;
  };
  const Vector a = force(first), b = force(second), again = force(first);
  EXPECT_EQ(a, again);
  // Elements 0, 4, ... against 1, 6, ...: no shared element, forces far apart.
  EXPECT_GT((a - b).norm(), 0.1 * a.norm());
}

// The element loops on 2 threads evaluate elements in parallel but sum them in element order, so
// force, tangent, energy and the reported smallest det F are the same bits as on 1 thread; with
// element weights (muscle stiffening) and when an element is inverted too.
TEST(SolidModel, TwoThreadsGiveBitForBitTheResultOfOne) {
  const Mesh mesh = distorted_box();
  SolidModel model(mesh, mooney_rivlin(), Formulation::mean_dilatation, kDensity,
                   constraints(mesh));
  const Vector u = displacement_field(mesh, deformation);
  std::vector<double> weights(mesh.num_elements(), 0.0);
  for (std::size_t e = 0; e < weights.size(); e += 3) weights[e] = 0.5 + 0.1 * e;

  struct Result {
    Vector f, f_weighted;
    std::vector<double> K, K_weighted;
    double energy = 0.0;
    double min_J = 0.0;
  };
  auto evaluate = [&](int threads) {
    model.set_threads(threads);
    EXPECT_EQ(model.threads(), threads);
    Result r;
    SymmetricMatrix K(model.pattern());
    const AssemblyStatus status = model.assemble(u, r.f, &K, &r.energy);
    EXPECT_TRUE(status.ok);
    r.min_J = status.min_J;
    r.K = K.values();
    r.f_weighted = Vector::Zero(u.size());
    EXPECT_TRUE(model.add_weighted(u, weights, r.f_weighted, nullptr).ok);
    Vector f_weighted = Vector::Zero(u.size());
    SymmetricMatrix K_weighted(model.pattern());
    EXPECT_TRUE(model.add_weighted(u, weights, f_weighted, &K_weighted).ok);
    r.K_weighted = K_weighted.values();
    return r;
  };
  const Result one = evaluate(1), two = evaluate(2);
  EXPECT_EQ(one.f, two.f);
  EXPECT_EQ(one.K, two.K);
  EXPECT_EQ(one.energy, two.energy);
  EXPECT_EQ(one.min_J, two.min_J);
  EXPECT_EQ(one.f_weighted, two.f_weighted);
  EXPECT_EQ(one.K_weighted, two.K_weighted);

  // Inverting one element: both report the same first inverted element.
  Vector crushed = u;
  const Hex8& element = mesh.elements[5];
  crushed.segment<3>(3 * element[6]) =
      mesh.nodes[element[0]] - mesh.nodes[element[6]] - Vec3(1e-3, 1e-3, 1e-3);
  Vector f;
  model.set_threads(1);
  const AssemblyStatus s1 = model.assemble(crushed, f, nullptr);
  model.set_threads(2);
  const AssemblyStatus s2 = model.assemble(crushed, f, nullptr);
  EXPECT_FALSE(s1.ok);
  EXPECT_FALSE(s2.ok);
  EXPECT_EQ(s1.inverted_element, s2.inverted_element);
  SymmetricMatrix K(model.pattern());
  model.set_threads(1);
  const AssemblyStatus t1 = model.assemble(crushed, f, &K);
  model.set_threads(2);
  const AssemblyStatus t2 = model.assemble(crushed, f, &K);
  EXPECT_FALSE(t1.ok);
  EXPECT_FALSE(t2.ok);
  EXPECT_EQ(t1.inverted_element, s1.inverted_element);
  EXPECT_EQ(t2.inverted_element, s1.inverted_element);
  EXPECT_EQ(t1.min_J, s1.min_J);
  EXPECT_EQ(t2.min_J, s1.min_J);
  EXPECT_THROW(model.set_threads(0), std::invalid_argument);
}

TEST(SolidModel, RigidMotionLeavesNoInternalForce) {
  const Mesh mesh = distorted_box();
  const SolidModel model(mesh, mooney_rivlin(), Formulation::mean_dilatation, kDensity, {});
  const Mat3 R = Eigen::AngleAxisd(1.2, Vec3(0.2, 1, -0.5).normalized()).toRotationMatrix();
  const Vector u = displacement_field(
      mesh, [&](const Vec3& X) { return Vec3((R - Mat3::Identity()) * X + Vec3(0.01, 0, -0.02)); });
  Vector f;
  ASSERT_TRUE(model.assemble(u, f, nullptr).ok);
  // Compare with the forces of the deformed state: stress round-off is ~1e-12 of kPa stresses.
  Vector f_deformed;
  ASSERT_TRUE(model.assemble(displacement_field(mesh, deformation), f_deformed, nullptr).ok);
  EXPECT_LT(f.norm(), 1e-10 * f_deformed.norm());
}

TEST(SolidModel, InvertedElementIsReported) {
  const Mesh mesh = make_box(Vec3::Zero(), Vec3(kLx, kLy, kLz), 3, 2, 2);
  const SolidModel model(mesh, mooney_rivlin(), Formulation::standard, kDensity, {});
  Vector u = Vector::Zero(model.num_dofs());
  // The box corner (3, 2, 2) belongs to the last element only: move it 1 mm beyond the
  // element's opposite corner, turning the element inside out.
  const Hex8& element = mesh.elements.back();
  const Vec3 target = mesh.nodes[element[0]] - Vec3(1e-3, 1e-3, 1e-3);
  u.segment<3>(3 * element[6]) = target - mesh.nodes[element[6]];
  Vector f;
  const AssemblyStatus status = model.assemble(u, f, nullptr);
  EXPECT_FALSE(status.ok);
  EXPECT_EQ(status.inverted_element, mesh.num_elements() - 1);
  EXPECT_LE(status.min_J, 0.0);
  // The same through the tangent path.
  SymmetricMatrix K(model.pattern());
  const AssemblyStatus with_tangent = model.assemble(u, f, &K);
  EXPECT_FALSE(with_tangent.ok);
  EXPECT_EQ(with_tangent.inverted_element, mesh.num_elements() - 1);
  EXPECT_LE(with_tangent.min_J, 0.0);
}

// u^T M u for a rigid unit translation is the kinetic-energy mass of the body.
double translation_mass(const SymmetricMatrix& M, int direction) {
  Vector u = Vector::Zero(M.pattern().size);
  for (int i = direction; i < u.size(); i += 3) u[i] = 1.0;
  return u.dot(M.multiply(u));
}

TEST(SolidModel, MassMatricesCarryTheTotalMassAndAreSymmetricPositiveDefinite) {
  // No constraints, so that the matrices over the free dofs are the whole mass matrices.
  const SolidModel regular(make_box(Vec3::Zero(), Vec3(kLx, kLy, kLz), 3, 2, 2), mooney_rivlin(),
                           Formulation::standard, kDensity, {});
  EXPECT_NEAR(regular.total_mass(), kDensity * kLx * kLy * kLz, 1e-14);  // kg, ~1e-2 of it
  const SolidModel distorted(distorted_box(), mooney_rivlin(), Formulation::standard, kDensity, {});

  for (const SolidModel* model : {&regular, &distorted}) {
    const double mass = model->total_mass();
    EXPECT_NEAR(mass, kDensity * model->reference_volume(), 1e-15);
    for (bool lumped : {false, true}) {
      SCOPED_TRACE(lumped ? "lumped" : "consistent");
      const SymmetricMatrix M = model->mass_matrix(lumped);
      // Sums of ~100 positive terms: relative round-off ~1e-15.
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(translation_mass(M, d), mass, 1e-13 * mass);

      const Eigen::MatrixXd dense = M.to_dense();
      EXPECT_EQ(dense, dense.transpose());
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense, Eigen::EigenvaluesOnly);
      // u^T M u >= sum_e lambda_min(M_e) |u_e|^2 and lambda_min(M_e) = m_e / 216 for a hex8
      // consistent mass (1/6 per direction), so lambda_min(M) >= m_e / 216 = mass / 2592 here;
      // the bound below is 14x lower and still ~1e10 times the round-off level.
      EXPECT_GT(eig.eigenvalues().minCoeff(), 1e-3 * mass / model->mesh().num_nodes());
      if (lumped) {
        EXPECT_EQ((dense - Eigen::MatrixXd(dense.diagonal().asDiagonal())).norm(), 0.0);
      }
    }
  }
}

TEST(SolidModel, CurrentVolumeIsExactForAffineDeformations) {
  const Mesh mesh = distorted_box();
  const SolidModel model(mesh, mooney_rivlin(), Formulation::standard, kDensity, {});
  const double V = model.reference_volume();
  // The distortion changes the volume a little, not much.
  EXPECT_NEAR(V, kLx * kLy * kLz, 0.05 * kLx * kLy * kLz);
  // 2x2x2 Gauss integrates J of a trilinear map exactly: only round-off (~1e-16 relative).
  EXPECT_NEAR(model.current_volume(Vector::Zero(model.num_dofs())), V, 1e-14 * V);

  Mat3 A;
  A << 1.3, 0.3, -0.1, 0.05, 0.8, 0.2, 0.1, -0.25, 1.15;
  ASSERT_GT(A.determinant(), 0.5);
  ASSERT_GT(std::abs(A.determinant() - 1.0), 0.05);
  const Vector u =
      displacement_field(mesh, [&](const Vec3& X) { return Vec3((A - Mat3::Identity()) * X); });
  EXPECT_NEAR(model.current_volume(u), A.determinant() * V, 1e-13 * V);
  // And under the non-affine deformation it is positive and not simply det(A) V.
  EXPECT_GT(model.current_volume(displacement_field(mesh, deformation)), 0.0);
}

// The volume from the boundary faces is the elements' int J dV, summed over their 2 x 2 x 2
// Gauss points (exact for trilinear maps), under a non-affine deformation of a distorted box.
TEST(SolidModel, CurrentVolumeEqualsTheElementsGaussSum) {
  const Mesh mesh = distorted_box();
  const SolidModel model(mesh, mooney_rivlin(), Formulation::standard, kDensity, {});
  const Vector u = displacement_field(mesh, deformation);
  double expected = 0.0;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    hex8::ElementCoords X, x;
    for (int a = 0; a < 8; ++a) {
      const int n = mesh.elements[e][a];
      X.row(a) = mesh.nodes[n].transpose();
      x.row(a) = (mesh.nodes[n] + u.segment<3>(3 * n)).transpose();
    }
    const ElementGeometry g = make_element_geometry(X);
    for (int q = 0; q < 8; ++q)
      expected += g.weight[q] * (x.transpose() * g.dN_dX[q]).determinant();
  }
  ASSERT_GT(std::abs(expected - model.reference_volume()), 1e-3 * expected);  // not the rest one
  // Two exact integrations summed in different orders: round-off, about 1e-16 of the terms.
  EXPECT_NEAR(model.current_volume(u), expected, 1e-13 * expected);
}

}  // namespace
}  // namespace tongue::fem
