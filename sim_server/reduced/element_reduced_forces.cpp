#include "reduced/element_reduced_forces.hpp"

#include <stdexcept>
#include <string>

namespace tongue::reduced {

Eigen::MatrixXd element_reduced_forces(const fem::SolidModel& solid, const fem::Vector& origin,
                                       const Eigen::MatrixXd& modes,
                                       const Eigen::MatrixXd& snapshots) {
  const fem::Mesh& mesh = solid.mesh();
  const Eigen::Index n = 3 * mesh.num_nodes(), k = modes.cols(), S = snapshots.cols();
  if (origin.size() != n || modes.rows() != n || snapshots.rows() != n)
    throw std::invalid_argument("element reduced forces: origin, modes and snapshots need " +
                                std::to_string(n) + " rows (3 per node)");
  Eigen::MatrixXd g(S * k, mesh.num_elements());
  Eigen::Matrix<double, 24, Eigen::Dynamic> phi_e(24, k);  // the modes on one element's dofs
  fem::ElementVector f;
  for (Eigen::Index s = 0; s < S; ++s) {
    const fem::Vector u = origin + snapshots.col(s);
    for (int e = 0; e < mesh.num_elements(); ++e) {
      if (!solid.element_force(e, u, f))
        throw std::runtime_error("element reduced forces: element " + std::to_string(e) +
                                 " inverted at snapshot " + std::to_string(s));
      const fem::Hex8& nodes = mesh.elements[e];
      for (int a = 0; a < 8; ++a) phi_e.middleRows(3 * a, 3) = modes.middleRows(3 * nodes[a], 3);
      g.block(s * k, e, k, 1) = phi_e.transpose() * f;
    }
  }
  return g;
}

}  // namespace tongue::reduced
