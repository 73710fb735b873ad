#pragma once
// Symmetric sparse matrices over the free dofs, stored as the upper triangle in compressed
// columns (the layout CHOLMOD reads with stype = +1). The pattern is built once per mesh and
// set of constraints; every matrix on it (tangent, mass, damping) is just a values array.
#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "fem/assembly/dof_map.hpp"
#include "fem/mesh/mesh.hpp"

namespace tongue::fem {

struct SparsityPattern {
  int size = 0;                   // number of rows and columns (free dofs)
  std::vector<int> column_start;  // size + 1 entries
  std::vector<int> row_index;     // sorted within each column, row <= column

  int nnz() const { return static_cast<int>(row_index.size()); }
  // Position of entry (row, col) with row <= col, or -1 when it is not in the pattern.
  int find(int row, int col) const;
};

// The pattern of all element couplings between free dofs, and for each element the position of
// each of its 24 x 24 local entries in the values array (-1 where a dof is prescribed or the
// entry lies in the lower triangle): assembly is then a plain scatter.
struct AssemblyPattern {
  SparsityPattern pattern;
  std::vector<std::array<int, 24 * 24>> element_scatter;  // [element][24 * row + col]
};

// extra_node_pairs couples nodes that share no element (e.g. consecutive nodes of a muscle fibre).
AssemblyPattern build_assembly_pattern(
    const Mesh& mesh, const DofMap& dofs,
    const std::vector<std::pair<int, int>>& extra_node_pairs = {});

// For each node, the nodes its free dofs are coupled to by the pattern's entries (in either
// triangle, itself included when it has a stored entry), ascending and without repeats: the
// rows of a matrix on the pattern taken in 3 x 3 node blocks.
std::vector<std::vector<int>> coupled_nodes(const SparsityPattern& pattern, const DofMap& dofs);

class SymmetricMatrix {
 public:
  explicit SymmetricMatrix(std::shared_ptr<const SparsityPattern> pattern);

  const SparsityPattern& pattern() const { return *pattern_; }
  std::shared_ptr<const SparsityPattern> shared_pattern() const { return pattern_; }
  std::vector<double>& values() { return values_; }
  const std::vector<double>& values() const { return values_; }
  void set_zero();

  // y = A x using both triangles.
  Vector multiply(const Vector& x) const;
  // y += A x, into a vector of the right size (no allocation).
  void multiply_add(const Vector& x, Vector& y) const;
  // Y += A X for k vectors at once, X and Y row-major (size x k): one pass over the entries,
  // each applied to a row of k, instead of k passes.
  using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  void multiply_add(const RowMajorMatrix& X, RowMajorMatrix& Y) const;
  double diagonal(int i) const;
  // this = a * this + b * other (same pattern)
  void scale_and_add(double a, double b, const SymmetricMatrix& other);
  Eigen::MatrixXd to_dense() const;  // for tests and small problems

 private:
  std::shared_ptr<const SparsityPattern> pattern_;
  std::vector<double> values_;
};

// Adds a 3 x 3 block coupling two nodes to K (free dofs only; rows or columns of prescribed dofs
// are skipped). block(c, d) is d2E / du_{a,c} du_{b,d}: row component c of node_a, column
// component d of node_b.
//  - node_a == node_b: the diagonal block; it must be symmetric and only its entries with
//    c <= d are read (those are the ones the upper-triangle storage holds).
//  - node_a != node_b: adds block at (node_a, node_b) AND its transpose at (node_b, node_a),
//    i.e. the full symmetric coupling. Call it once per pair: calling it also for (b, a) with
//    block^T would add the coupling twice.
// Throws std::logic_error when a needed entry is not in the pattern: the pattern must have been
// built with the pair in extra_node_pairs, or the nodes must share an element.
void add_node_block(SymmetricMatrix& K, const DofMap& dofs, int node_a, int node_b,
                    const Mat3& block);

}  // namespace tongue::fem
