// DofMap: free dofs numbered consecutively in global order, prescribed values kept, gather and
// scatter inverse to each other on the free dofs, bad input rejected.
#include <gtest/gtest.h>

#include <stdexcept>

#include "fem/assembly/dof_map.hpp"

namespace tongue::fem {
namespace {

TEST(DofMap, NumbersFreeDofsConsecutivelyInGlobalOrder) {
  // 4 nodes = 12 dofs; prescribe node 0 fully, node 2 in y only.
  const DofMap dofs(4, {{0, 0, 0.1}, {0, 1, 0.2}, {0, 2, 0.3}, {2, 1, -0.5}});
  EXPECT_EQ(dofs.num_dofs(), 12);
  EXPECT_EQ(dofs.num_free(), 8);
  EXPECT_EQ(dofs.prescribed_dofs(), (std::vector<int>{0, 1, 2, 7}));
  EXPECT_EQ(dofs.free_dofs(), (std::vector<int>{3, 4, 5, 6, 8, 9, 10, 11}));
  int expected = 0;
  for (int dof = 0; dof < 12; ++dof) {
    const bool prescribed = dof < 3 || dof == 7;
    EXPECT_EQ(dofs.is_free(dof), !prescribed) << "dof " << dof;
    EXPECT_EQ(dofs.free_index(dof), prescribed ? -1 : expected++) << "dof " << dof;
  }
  Vector values = Vector::Zero(12);
  values << 0.1, 0.2, 0.3, 0, 0, 0, 0, -0.5, 0, 0, 0, 0;
  EXPECT_EQ(dofs.prescribed_values(), values);  // exact: copied, not computed
}

TEST(DofMap, DofPrescribedTwiceKeepsTheLastValue) {
  const DofMap dofs(2, {{1, 2, 1.0}, {1, 2, 3.0}});
  EXPECT_EQ(dofs.num_free(), 5);
  EXPECT_EQ(dofs.prescribed_dofs(), (std::vector<int>{5}));
  EXPECT_EQ(dofs.prescribed_values()[5], 3.0);
}

TEST(DofMap, GatherAndScatterAreInverseOnTheFreeDofs) {
  const DofMap dofs(5, {{1, 0, 0.0}, {1, 2, 0.0}, {4, 1, 0.0}});
  const Vector full = Vector::LinSpaced(15, 1.0, 15.0);
  const Vector free = dofs.gather_free(full);
  ASSERT_EQ(free.size(), 12);
  for (int i = 0; i < dofs.num_free(); ++i) EXPECT_EQ(free[i], full[dofs.free_dofs()[i]]);

  Vector target = Vector::Constant(15, -7.0);
  dofs.scatter_free(free, target);
  for (int dof = 0; dof < 15; ++dof) {
    // Free entries come back exactly; prescribed entries are left untouched.
    EXPECT_EQ(target[dof], dofs.is_free(dof) ? full[dof] : -7.0) << "dof " << dof;
  }
  EXPECT_EQ(dofs.gather_free(target), free);
}

TEST(DofMap, NoConstraintsMeansAllFree) {
  const DofMap dofs(3, {});
  EXPECT_EQ(dofs.num_free(), 9);
  EXPECT_TRUE(dofs.prescribed_dofs().empty());
  const Vector v = Vector::Random(9);
  EXPECT_EQ(dofs.gather_free(v), v);
}

TEST(DofMap, RejectsNodesAndComponentsOutOfRange) {
  EXPECT_THROW(DofMap(3, {{-1, 0, 0.0}}), std::invalid_argument);
  EXPECT_THROW(DofMap(3, {{3, 0, 0.0}}), std::invalid_argument);
  EXPECT_THROW(DofMap(3, {{0, -1, 0.0}}), std::invalid_argument);
  EXPECT_THROW(DofMap(3, {{0, 3, 0.0}}), std::invalid_argument);
  EXPECT_NO_THROW(DofMap(3, {{2, 2, 0.0}}));
}

}  // namespace
}  // namespace tongue::fem
