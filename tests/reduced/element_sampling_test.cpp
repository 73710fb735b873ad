// Energy-conserving sampling and weighting: a few elements with positive weights whose reduced
// forces reproduce the whole mesh's over the snapshots, to the tolerance asked.
#include "reduced/element_sampling.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"
#include "reduced/element_reduced_forces.hpp"
#include "reduced/pod_basis.hpp"

namespace tongue::reduced {
namespace {

// The misfit over the snapshots, each scaled by its own target (by default its mesh force),
// computed here from g.
double relative_misfit(const Eigen::MatrixXd& g, int k, const ElementSample& sample,
                       const fem::Vector* target = nullptr) {
  fem::Vector w = fem::Vector::Zero(g.cols());
  for (std::size_t j = 0; j < sample.elements.size(); ++j)
    w[sample.elements[j]] = sample.weights[static_cast<Eigen::Index>(j)];
  double sum = 0.0;
  const Eigen::Index S = g.rows() / k;
  for (Eigen::Index s = 0; s < S; ++s) {
    const auto block = g.middleRows(s * k, k);
    const fem::Vector whole =
        target ? fem::Vector(target->segment(s * k, k)) : fem::Vector(block.rowwise().sum());
    sum += (block * w - whole).squaredNorm() / whole.squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(S));
}

// A cantilever-like box bent and twisted by smooth fields of random amplitudes: 40 snapshots,
// their 3 leading modes, and its elements' reduced forces over them.
struct BentBox {
  Eigen::MatrixXd g;
  int k = 0;
};
BentBox bent_box() {
  const fem::Mesh mesh = fem::make_box(fem::Vec3::Zero(), {0.06, 0.02, 0.02}, 8, 3, 3);
  const fem::SolidModel solid(mesh, fem::make_material("mooney_rivlin5", {}),
                              fem::Formulation::mean_dilatation, 1000.0, {});
  const Eigen::Index n = 3 * mesh.num_nodes();
  Eigen::MatrixXd fields(n, 3);
  for (int a = 0; a < mesh.num_nodes(); ++a) {
    const fem::Vec3& x = mesh.nodes[a];
    const double s = x.x() / 0.06;
    fields.block<3, 1>(3 * a, 0) = fem::Vec3(0.0, 0.0, s * s);                         // bending
    fields.block<3, 1>(3 * a, 1) = fem::Vec3(0.0, s * s, 0.0);                         // sideways
    fields.block<3, 1>(3 * a, 2) = s * fem::Vec3(0.0, -(x.z() - 0.01), x.y() - 0.01);  // twist
  }
  std::srand(7);
  const Eigen::MatrixXd amplitudes =
      Eigen::DiagonalMatrix<double, 3>(4e-3, 3e-3, 0.3) * Eigen::MatrixXd::Random(3, 40);
  const Eigen::MatrixXd snapshots = fields * amplitudes;
  const PodBasis pod = pod_basis(snapshots, 0.999999);
  BentBox box;
  box.k = static_cast<int>(pod.modes.cols());
  box.g = element_reduced_forces(solid, fem::Vector::Zero(n), pod.modes, snapshots);
  return box;
}

TEST(ElementSampling, AFewElementsReproduceTheMeshsReducedForces) {
  const BentBox box = bent_box();
  const Eigen::MatrixXd& g = box.g;
  const int k = box.k;
  ASSERT_EQ(k, 3);

  for (const double tolerance : {0.05, 0.01}) {
    SCOPED_TRACE(tolerance);
    const ElementSample sample = sample_elements(g, k, tolerance);
    ASSERT_TRUE(sample.within_tolerance);
    ASSERT_EQ(static_cast<Eigen::Index>(sample.elements.size()), sample.weights.size());
    // Few elements: far fewer than the mesh's 72 (the path adds one at a time and stops at the
    // tolerance); positive weights on distinct elements in ascending order.
    EXPECT_LT(sample.elements.size(), 36u);
    EXPECT_GE(sample.elements.size(), 1u);
    EXPECT_GT(sample.weights.minCoeff(), 0.0);
    for (std::size_t j = 1; j < sample.elements.size(); ++j)
      EXPECT_LT(sample.elements[j - 1], sample.elements[j]);
    // The misfit it reports is the one its weights give, and within the tolerance.
    const double misfit = relative_misfit(g, k, sample);
    EXPECT_NEAR(sample.relative_error, misfit, 1e-9);
    EXPECT_LE(misfit, tolerance);
  }
  // A tighter tolerance takes at least as many elements.
  EXPECT_LE(sample_elements(g, k, 0.05).elements.size(),
            sample_elements(g, k, 0.01).elements.size());
}

TEST(ElementSampling, ReproducesAGivenTargetWithOtherCandidates) {
  // Candidates that are not the mesh's elements: each element's reduced forces times a factor
  // of its own in [0.5, 1.5], weighed to reproduce the whole mesh's (which the candidates do
  // exactly with weights 1 / factor).
  const BentBox box = bent_box();
  const fem::Vector whole = box.g.rowwise().sum();
  std::srand(11);
  const fem::Vector factors = 1.0 + 0.5 * fem::Vector::Random(box.g.cols()).array();
  const Eigen::MatrixXd candidates = box.g * factors.asDiagonal();
  for (const double tolerance : {0.05, 0.01}) {
    SCOPED_TRACE(tolerance);
    const ElementSample sample = sample_elements(candidates, box.k, tolerance, whole);
    ASSERT_TRUE(sample.within_tolerance);
    EXPECT_LT(sample.elements.size(), 36u);
    EXPECT_GT(sample.weights.minCoeff(), 0.0);
    const double misfit = relative_misfit(candidates, box.k, sample, &whole);
    EXPECT_NEAR(sample.relative_error, misfit, 1e-9);
    EXPECT_LE(misfit, tolerance);
  }
}

TEST(ElementSampling, RefusesWhatIsNoSamplingProblem) {
  const Eigen::MatrixXd g = Eigen::MatrixXd::Ones(6, 4);
  EXPECT_THROW(sample_elements(g, 4, 0.01), std::invalid_argument);  // 6 rows, 4 modes
  EXPECT_THROW(sample_elements(g, 3, 0.0), std::invalid_argument);
  EXPECT_THROW(sample_elements(g, 3, 1.0), std::invalid_argument);
  EXPECT_THROW(sample_elements(Eigen::MatrixXd(6, 0), 3, 0.01), std::invalid_argument);
  EXPECT_THROW(sample_elements(Eigen::MatrixXd::Zero(6, 4), 3, 0.01), std::invalid_argument);
  // A target of another size, or without force.
  EXPECT_THROW(sample_elements(g, 3, 0.01, fem::Vector::Ones(5)), std::invalid_argument);
  EXPECT_THROW(sample_elements(g, 3, 0.01, fem::Vector::Zero(6)), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::reduced
