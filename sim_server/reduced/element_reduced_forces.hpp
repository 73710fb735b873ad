#pragma once
// The elements' reduced internal forces over the training snapshots: the system that
// hyper-reduction weighs the elements by (energy-conserving sampling and weighting, Farhat,
// Avery, Chapman & Cortial 2014, Int. J. Numer. Meth. Eng. 98, eq. 26). For snapshot s and
// element e, the k reduced forces Phi_e^T f_e(u_s) of the element alone, Phi_e the modes' rows
// on its 24 dofs and u_s = origin + snapshot s; stacked snapshot by snapshot into a column per
// element. With every weight 1 the columns add up to Phi^T f_int(u_s), the reduced internal force
// of the whole mesh.
#include "fem/assembly/solid_model.hpp"
#include "fem/types.hpp"

namespace tongue::reduced {

// (S k) x E: row s k + i holds mode i's component of each element's force at snapshot s.
// modes: 3N x k; snapshots: 3N x S, displacements from origin [m]. Throws std::invalid_argument
// for sizes that do not fit the solid, std::runtime_error at an inverted element (naming the
// snapshot and the element).
Eigen::MatrixXd element_reduced_forces(const fem::SolidModel& solid, const fem::Vector& origin,
                                       const Eigen::MatrixXd& modes,
                                       const Eigen::MatrixXd& snapshots);

}  // namespace tongue::reduced
