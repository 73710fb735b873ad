#include "fem/assembly/rigid_motions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>  // cross()
#include <Eigen/SVD>

namespace tongue::fem {
namespace {

constexpr double kRankTolerance = 1e-9;  // relative to the largest singular value

const char* const kAxes[3] = {"x", "y", "z"};

}  // namespace

std::vector<std::string> free_rigid_motions(const std::vector<Vec3>& nodes,
                                            const std::vector<PrescribedDof>& prescribed) {
  if (nodes.empty()) return {};
  Vec3 centre = Vec3::Zero();
  for (const Vec3& x : nodes) centre += x;
  centre /= static_cast<double>(nodes.size());
  double size = 0.0;
  for (const Vec3& x : nodes) size = std::max(size, (x - centre).norm());
  // Column k: rigid mode k at the prescribed dofs; rotations scaled by the body's size so that
  // the six columns have like magnitudes.
  Eigen::MatrixXd modes(static_cast<Eigen::Index>(prescribed.size()), 6);
  for (std::size_t i = 0; i < prescribed.size(); ++i) {
    const PrescribedDof& p = prescribed[i];
    const Vec3 r = (nodes[p.node] - centre) / (size > 0.0 ? size : 1.0);
    for (int k = 0; k < 3; ++k) {
      modes(static_cast<Eigen::Index>(i), k) = k == p.component ? 1.0 : 0.0;
      modes(static_cast<Eigen::Index>(i), 3 + k) = Vec3(Vec3::Unit(k)).cross(r)[p.component];
    }
  }
  // The six motions one by one first: they name what is free in words.
  std::vector<std::string> free;
  const double scale = std::max(1.0, modes.norm());
  for (int k = 0; k < 6; ++k) {
    if (modes.col(k).norm() > kRankTolerance * scale) continue;
    if (k < 3) {
      free.push_back("translation along " + std::string(kAxes[k]));
    } else {
      char text[120];
      std::snprintf(text, sizeof text, "rotation about %s through (%.4g, %.4g, %.4g) m",
                    kAxes[k - 3], centre.x(), centre.y(), centre.z());
      free.push_back(text);
    }
  }
  // Then the dimension of all free motions: a hinge off the centroid frees a rotation about
  // another axis, a combination of the six.
  int held = 0;
  if (modes.rows() > 0) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(modes);
    const Eigen::VectorXd& sigma = svd.singularValues();
    for (Eigen::Index k = 0; k < sigma.size(); ++k)
      if (sigma[k] > kRankTolerance * scale) ++held;
  }
  const int more = 6 - held - static_cast<int>(free.size());
  if (more > 0)
    free.push_back(std::to_string(more) + " rigid motion" + (more > 1 ? "s" : "") +
                   " combining translations and rotations");
  return free;
}

}  // namespace tongue::fem
