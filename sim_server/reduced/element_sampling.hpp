#pragma once
// Energy-conserving sampling and weighting of the elements (Farhat, Avery, Chapman & Cortial
// 2014, Int. J. Numer. Meth. Eng. 98, sec. 4): a few elements and non-negative weights whose
// weighted reduced internal forces reproduce the whole mesh's over the training snapshots,
//   || G w - G 1 || <= tolerance || G 1 ||,  w >= 0, few w_e > 0,
// G the elements' reduced forces (element_reduced_forces.hpp). Each snapshot's block of rows is
// scaled by the norm of its own mesh force first, so that every snapshot counts alike. Solved by
// the non-negative LASSO path of least-angle regression (Efron, Hastie, Johnstone & Tibshirani
// 2004, Ann. Stat. 32), VIGRA's leastAngleRegression: elements enter one at a time, and the
// first point of the path within the tolerance is kept, which is the sparse solution that
// Lawson & Hanson's non-negative least squares gives when stopped early, as the paper does.
#include <vector>

#include "fem/types.hpp"

namespace tongue::reduced {

struct ElementSample {
  std::vector<int> elements;      // ascending
  fem::Vector weights;            // > 0, one per sampled element
  double relative_error = 0.0;    // || G w - G 1 || / || G 1 || over the scaled rows
  bool within_tolerance = false;  // false: the whole path stayed above it (the last point kept)
};

// g: (S k) x E, snapshot s in rows s k .. s k + k - 1 (element_reduced_forces). Throws
// std::invalid_argument for a size that is not a multiple of k, no element, or a tolerance
// outside (0, 1).
ElementSample sample_elements(const Eigen::MatrixXd& g, int k, double tolerance);

// The same with another target than G 1: the columns of g weighed to reproduce `target` (S k
// values, each snapshot's block scaled by its own norm), e.g. the whole mesh's reduced forces by
// candidates that are not its elements. Throws std::invalid_argument also for a target of
// another size or without force.
ElementSample sample_elements(const Eigen::MatrixXd& g, int k, double tolerance,
                              const fem::Vector& target);

}  // namespace tongue::reduced
