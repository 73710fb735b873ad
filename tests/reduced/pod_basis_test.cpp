// Proper orthogonal decomposition: the modes of snapshots of known rank, the projection of the
// snapshots onto them, and the energy left out by a truncated basis.
#include "reduced/pod_basis.hpp"

#include <gtest/gtest.h>

namespace tongue::reduced {
namespace {

// 200 snapshots of 60 values, combinations of 3 fixed vectors with random weights.
Eigen::MatrixXd rank_three() {
  std::srand(7);
  const Eigen::MatrixXd shapes = Eigen::MatrixXd::Random(60, 3);
  return shapes * Eigen::MatrixXd::Random(3, 200);
}

TEST(PodBasis, SnapshotsOfRankThreeNeedThreeModesThatReproduceThem) {
  const Eigen::MatrixXd s = rank_three();
  const PodBasis b = pod_basis(s, 0.9999);
  ASSERT_EQ(b.modes.cols(), 3);
  EXPECT_LT((b.modes.transpose() * b.modes - Eigen::MatrixXd::Identity(3, 3)).norm(), 1e-13);
  // Projection reproduces every snapshot: the fourth singular value is round-off of the SVD
  // (~1e-15 of the first for a matrix of norm ~100).
  const Eigen::MatrixXd back = b.modes * (b.modes.transpose() * s);
  EXPECT_LT((back - s).norm(), 1e-11 * s.norm());
  EXPECT_NEAR(b.captured, 1.0, 1e-14);
  EXPECT_LT(b.singular_values[3], 1e-12 * b.singular_values[0]);
}

// For any snapshots, the energy the projection leaves out is that of the dropped singular
// values (the Eckart-Young theorem), at most 1 - fraction of the whole.
TEST(PodBasis, TheEnergyLeftOutIsThatOfTheDroppedModes) {
  std::srand(11);
  const Eigen::MatrixXd s = Eigen::MatrixXd::Random(80, 50);
  for (const double fraction : {0.5, 0.9, 0.99}) {
    const PodBasis b = pod_basis(s, fraction);
    const Eigen::MatrixXd left = s - b.modes * (b.modes.transpose() * s);
    const double dropped =
        b.singular_values.tail(b.singular_values.size() - b.modes.cols()).squaredNorm();
    EXPECT_NEAR(left.squaredNorm(), dropped, 1e-10 * s.squaredNorm());
    EXPECT_LE(left.squaredNorm(), (1.0 - fraction) * s.squaredNorm() * (1.0 + 1e-12));
    EXPECT_GE(b.captured, fraction);
    // One mode fewer would not hold the fraction.
    const double fewer = b.singular_values.head(b.modes.cols() - 1).squaredNorm();
    EXPECT_LT(fewer, fraction * s.squaredNorm());
  }
}

TEST(PodBasis, RefusesNoSnapshotsZeroSnapshotsAndBadFractions) {
  EXPECT_THROW(pod_basis(Eigen::MatrixXd(), 0.9), std::invalid_argument);
  EXPECT_THROW(pod_basis(Eigen::MatrixXd::Zero(4, 3), 0.9), std::invalid_argument);
  EXPECT_THROW(pod_basis(Eigen::MatrixXd::Ones(4, 3), 0.0), std::invalid_argument);
  EXPECT_THROW(pod_basis(Eigen::MatrixXd::Ones(4, 3), 1.5), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::reduced
