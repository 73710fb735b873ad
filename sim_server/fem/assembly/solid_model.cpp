#include "fem/assembly/solid_model.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace tongue::fem {

SolidModel::SolidModel(Mesh mesh, std::shared_ptr<const Material> material, Formulation formulation,
                       double density, const std::vector<PrescribedDof>& prescribed,
                       const std::vector<std::pair<int, int>>& extra_node_pairs)
    : mesh_(std::move(mesh)),
      material_(std::move(material)),
      formulation_(formulation),
      density_(density),
      dofs_(mesh_.num_nodes(), prescribed) {
  if (!material_) throw std::invalid_argument("solid model needs a material");
  if (!(density_ > 0.0)) throw std::invalid_argument("density must be positive [kg/m^3]");
  if (formulation_ == Formulation::mean_dilatation && material_->as_uncoupled() == nullptr) {
    throw std::invalid_argument("material '" + material_->name() +
                                "' has no isochoric/volumetric split: use the standard "
                                "formulation");
  }
  rest_positions_.resize(3 * mesh_.num_nodes());
  for (int n = 0; n < mesh_.num_nodes(); ++n) rest_positions_.segment<3>(3 * n) = mesh_.nodes[n];

  geometry_.reserve(mesh_.elements.size());
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    try {
      geometry_.push_back(make_element_geometry(element_coords(e, rest_positions_)));
    } catch (const std::invalid_argument& err) {
      throw std::invalid_argument("element " + std::to_string(e) + ": " + err.what());
    }
  }
  AssemblyPattern assembly = build_assembly_pattern(mesh_, dofs_, extra_node_pairs);
  pattern_ = std::make_shared<const SparsityPattern>(std::move(assembly.pattern));
  element_scatter_ = std::move(assembly.element_scatter);
}

hex8::ElementCoords SolidModel::element_coords(int e, const Vector& positions) const {
  hex8::ElementCoords X;
  const Hex8& nodes = mesh_.elements[e];
  for (int a = 0; a < 8; ++a) X.row(a) = positions.segment<3>(3 * nodes[a]).transpose();
  return X;
}

AssemblyStatus SolidModel::assemble(const Vector& u, Vector& internal_force,
                                    SymmetricMatrix* stiffness, double* strain_energy) const {
  internal_force.setZero(num_dofs());
  if (stiffness) stiffness->set_zero();
  if (strain_energy) *strain_energy = 0.0;
  return add_weighted(u, {}, internal_force, stiffness, strain_energy);
}

AssemblyStatus SolidModel::add_weighted(const Vector& u, const std::vector<double>& weights,
                                        Vector& internal_force, SymmetricMatrix* stiffness,
                                        double* strain_energy) const {
  if (!weights.empty() && static_cast<int>(weights.size()) != mesh_.num_elements()) {
    throw std::invalid_argument("element weights: one per element expected");
  }
  AssemblyStatus status;
  status.min_J = std::numeric_limits<double>::infinity();
  const Vector x = rest_positions_ + u;
  ElementResponse r;
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    const double w = weights.empty() ? 1.0 : weights[e];
    if (w == 0.0) continue;
    const bool ok = evaluate_element(geometry_[e], element_coords(e, x), *material_, formulation_,
                                     stiffness != nullptr, r);
    status.min_J = std::min(status.min_J, r.min_J);
    if (!ok) {
      status.ok = false;
      status.inverted_element = e;
      return status;
    }
    if (strain_energy) *strain_energy += w * r.energy;
    const Hex8& nodes = mesh_.elements[e];
    for (int a = 0; a < 8; ++a)
      internal_force.segment<3>(3 * nodes[a]) += w * r.force.segment<3>(3 * a);
    if (stiffness) {
      std::vector<double>& values = stiffness->values();
      const auto& scatter = element_scatter_[e];
      for (int i = 0; i < 24; ++i) {
        for (int j = 0; j < 24; ++j) {
          const int k = scatter[24 * i + j];
          if (k >= 0) values[k] += w * r.stiffness(i, j);
        }
      }
    }
  }
  return status;
}

SymmetricMatrix SolidModel::mass_matrix(bool lumped) const {
  SymmetricMatrix M(pattern_);
  std::vector<double>& values = M.values();
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    Eigen::Matrix<double, 8, 8> m =
        density_ * element_mass_pattern(element_coords(e, rest_positions_));
    if (lumped) {
      const Eigen::Matrix<double, 8, 1> row_sums = m.rowwise().sum();
      m = row_sums.asDiagonal();
    }
    const auto& scatter = element_scatter_[e];
    for (int a = 0; a < 8; ++a) {
      for (int b = 0; b < 8; ++b) {
        for (int c = 0; c < 3; ++c) {
          const int k = scatter[24 * (3 * a + c) + (3 * b + c)];
          if (k >= 0) values[k] += m(a, b);
        }
      }
    }
  }
  return M;
}

Vector SolidModel::body_force(const Vec3& acceleration) const {
  Vector f = Vector::Zero(num_dofs());
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    const Eigen::Matrix<double, 8, 1> s = element_shape_integrals(geometry_[e]);
    const Hex8& nodes = mesh_.elements[e];
    for (int a = 0; a < 8; ++a) f.segment<3>(3 * nodes[a]) += density_ * s(a) * acceleration;
  }
  return f;
}

double SolidModel::reference_volume() const {
  double v = 0.0;
  for (const ElementGeometry& g : geometry_) v += g.volume;
  return v;
}

double SolidModel::total_mass() const {
  return density_ * reference_volume();
}

double SolidModel::current_volume(const Vector& u) const {
  const Vector x = rest_positions_ + u;
  double v = 0.0;
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    const hex8::ElementCoords xe = element_coords(e, x);
    for (int q = 0; q < 8; ++q) {
      v += geometry_[e].weight[q] * (xe.transpose() * geometry_[e].dN_dX[q]).determinant();
    }
  }
  return v;
}

}  // namespace tongue::fem
