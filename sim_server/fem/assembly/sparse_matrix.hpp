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
  double diagonal(int i) const;
  // this = a * this + b * other (same pattern)
  void scale_and_add(double a, double b, const SymmetricMatrix& other);
  Eigen::MatrixXd to_dense() const;  // for tests and small problems

 private:
  std::shared_ptr<const SparsityPattern> pattern_;
  std::vector<double> values_;
};

}  // namespace tongue::fem
