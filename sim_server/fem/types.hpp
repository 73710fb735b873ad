#pragma once
// Small fixed-size types shared by the whole FEM core.
#include <Eigen/Core>
#include <Eigen/LU>  // determinant() and inverse() of the small fixed-size matrices

namespace tongue::fem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vector = Eigen::VectorXd;

// A second-order tensor flattened column-major, matching Eigen::Map over a Mat3:
// component (i, J) sits at index i + 3 J.
using Vec9 = Eigen::Matrix<double, 9, 1>;
// A fourth-order tensor A_{iJkL} = d2W / dF_iJ dF_kL as a 9x9 matrix on that flattening.
using Mat9 = Eigen::Matrix<double, 9, 9>;

constexpr int flat_index(int i, int J) {
  return i + 3 * J;
}

inline Eigen::Map<const Vec9> flatten(const Mat3& m) {
  return Eigen::Map<const Vec9>(m.data());
}

}  // namespace tongue::fem
