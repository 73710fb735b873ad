// Products of sparse columns held as runs of consecutive rows against the same vectors dense:
// runs that overlap in part, meet end to end, or miss each other.
#include "fem/solver/sparse_column.hpp"

#include <gtest/gtest.h>

#include <random>

namespace tongue::fem {
namespace {

constexpr int kSize = 60;

SparseColumn column_with(const std::vector<std::pair<int, int>>& ranges, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  SparseColumn c;
  for (const auto& [first, end] : ranges)
    for (int row = first; row < end; ++row) c.append(row, value(rng));
  return c;
}

Vector dense(const SparseColumn& c) {
  Vector v = Vector::Zero(kSize);
  c.subtract_from(-1.0, v);
  return v;
}

TEST(SparseColumn, AppendJoinsConsecutiveRowsAndLeavesOutZeros) {
  SparseColumn c;
  c.append(3, 1.0);
  c.append(4, 2.0);
  c.append(5, 0.0);  // left out: the run ends
  c.append(6, 3.0);
  c.append(9, 4.0);
  c.append(10, 5.0);
  ASSERT_EQ(c.runs.size(), 3u);
  EXPECT_EQ(c.runs[0].row, 3);
  EXPECT_EQ(c.runs[0].length, 2);
  EXPECT_EQ(c.runs[1].row, 6);
  EXPECT_EQ(c.runs[1].length, 1);
  EXPECT_EQ(c.runs[2].row, 9);
  EXPECT_EQ(c.runs[2].length, 2);
  EXPECT_EQ(c.values, (std::vector<double>{1.0, 2.0, 3.0, 4.0, 5.0}));
  Vector expected = Vector::Zero(kSize);
  expected[3] = 1.0, expected[4] = 2.0, expected[6] = 3.0, expected[9] = 4.0, expected[10] = 5.0;
  EXPECT_EQ(dense(c), expected);
}

TEST(SparseColumn, ProductsEqualTheDenseOnes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const std::vector<SparseColumn> columns{
      column_with({{2, 9}, {20, 31}, {40, 60}}, rng),
      column_with({{5, 22}, {30, 33}, {45, 50}, {55, 58}}, rng),  // in part over the first's
      column_with({{9, 20}, {31, 40}}, rng),                      // in its gaps, end to end
      column_with({{0, 60}}, rng),                                // one run over all
      SparseColumn{}};
  Vector y(kSize);
  for (int i = 0; i < kSize; ++i) y[i] = value(rng);
  // Sums of up to 60 products of numbers below 1, in other orders: round-off ~1e-14.
  for (const SparseColumn& a : columns) {
    EXPECT_NEAR(a.dot(y), dense(a).dot(y), 1e-14);
    Vector z = y;
    a.subtract_from(0.7, z);
    EXPECT_LT((z - (y - 0.7 * dense(a))).norm(), 1e-15);
    for (const SparseColumn& b : columns) {
      EXPECT_NEAR(dot(a, b), dense(a).dot(dense(b)), 1e-14);
      EXPECT_EQ(dot(a, b), dot(b, a));
    }
  }
}

}  // namespace
}  // namespace tongue::fem
