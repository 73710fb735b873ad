#pragma once
// A sparse vector whose nonzeros come in runs of consecutive rows. L^-1 b for a b with a few
// nonzeros is one: it fills the rows of the supernodes on the elimination-tree paths from b's
// entries to the root, and each supernode's rows are consecutive (SinglePrecisionFactor::
// forward_sparse). Products over runs are contiguous loops, which vectorize, where products
// entry by entry gather through an index.
#include <vector>

#include "fem/types.hpp"

namespace tongue::fem {

struct SparseColumn {
  struct Run {
    int row = 0;     // the first row
    int length = 0;  // rows row .. row + length - 1
  };
  std::vector<Run> runs;       // ascending and disjoint
  std::vector<double> values;  // the runs' entries, run after run

  // Appends a nonzero below the last one (a zero is left out).
  void append(int row, double value);
  double dot(const Vector& y) const;
  // y -= a w
  void subtract_from(double a, Vector& y) const;
};

// The inner product of two sparse columns, over the rows both runs cover.
double dot(const SparseColumn& a, const SparseColumn& b);

}  // namespace tongue::fem
