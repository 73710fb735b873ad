#pragma once
// The Galerkin projection of a symmetric sparse matrix onto the modes, Phi^T A Phi (k x k), for
// the matrices of one sparsity pattern: the reduced model's tangent, mass and damping.
//
// Why not a product with the stored triangle: the reduced tangent is formed whenever Newton
// contracts too slowly, and A Phi entry by entry adds a scalar times a row of k to a row of the
// product twice per stored entry, reading and writing rows of k each time. Here A is held as full
// rows of dense 3 x 3 node blocks (both triangles: each row of the product is one sum over its
// blocks), Phi row-major with its width padded to whole vectors, and each row block of A Phi is
// accumulated in registers, sixteen columns at a time; Phi^T (A Phi) is then one dense product
// by the BLAS. On the tongue's tangent (49 modes, reduced_benchmark) the projection took 1.7 ms
// instead of 3.7 ms, and forming the reduced tangent 2.7 ms instead of 4.3 ms. Blocks that hold
// no non-zero entry are skipped: about 40 % of the reduced tangent's, which holds the sampled
// elements' and the muscles' stiffness only.
//
// In single precision (a matrix that only steers Newton's corrections, such as the reduced
// Newton matrix) the products run on float copies: half the bytes to stream through the caches.
#include <Eigen/Core>
#include <vector>

#include "fem/assembly/dof_map.hpp"
#include "fem/assembly/sparse_matrix.hpp"

namespace tongue::reduced {

enum class Precision { double_precision, single_precision };

class GalerkinProjector {
 public:
  GalerkinProjector() = default;
  // phi: every dof x k (rows of prescribed dofs are not read); pattern over dofs' free dofs.
  // Throws std::invalid_argument when the sizes do not fit.
  GalerkinProjector(const fem::SparsityPattern& pattern, const fem::DofMap& dofs,
                    const Eigen::MatrixXd& phi);

  // Phi^T A Phi, symmetric to round-off and then made exactly so, its products in the precision
  // asked for (the result is double either way). A must be on the pattern given at
  // construction. Not thread-safe (it reuses its work arrays).
  Eigen::MatrixXd project(const fem::SymmetricMatrix& a,
                          Precision precision = Precision::double_precision) const;

 private:
  // Phi, its products with A, and A's blocks, in one precision.
  template <typename T>
  struct Work {
    std::vector<T> phi;      // 3 num_nodes x width_, row-major, zero-padded
    std::vector<T> blocks;   // 9 per block, row-major
    std::vector<T> product;  // A Phi, as phi
  };
  template <typename T>
  Eigen::MatrixXd project_in(const fem::SymmetricMatrix& a, Work<T>& work) const;

  int modes_ = 0, width_ = 0;           // k, and k rounded up to a multiple of 16
  std::vector<int> row_start_;          // per node, its blocks' range (num_nodes + 1 entries)
  std::vector<int> column_node_;        // per block, the node it couples its row's node to
  std::vector<int> position_, mirror_;  // per stored entry, its place in blocks and its
                                        // transpose's (-1 on the diagonal)
  mutable Work<double> double_;
  mutable Work<float> single_;  // made at the first single-precision projection
  // Per block, whether the matrix projected holds a non-zero entry in it; and, per node, the
  // range of its non-zero blocks in active_column_ and active_block_ (indices into blocks).
  mutable std::vector<char> nonzero_;
  mutable std::vector<int> active_start_, active_column_, active_block_;
};

}  // namespace tongue::reduced
