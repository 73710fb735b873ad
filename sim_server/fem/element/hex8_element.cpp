#include "fem/element/hex8_element.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>

#include "fem/element/hex8_batch.hpp"

namespace tongue::fem {

ElementGeometry make_element_geometry(const hex8::ElementCoords& X) {
  ElementGeometry g;
  const auto& rule = hex8::gauss_2x2x2();
  for (int q = 0; q < 8; ++q) {
    const hex8::ShapeGradients dN_dxi = hex8::reference_gradients(rule[q].xi);
    const Mat3 jac = X.transpose() * dN_dxi;  // dX/dxi
    const double det = jac.determinant();
    if (!(det > 0.0)) {
      throw std::invalid_argument(
          "element has a non-positive Jacobian determinant at a Gauss point");
    }
    g.dN_dX[q] = dN_dxi * jac.inverse();
    g.weight[q] = rule[q].weight * det;
    g.volume += g.weight[q];
  }
  return g;
}

namespace {

// Adds w * B^T A B to the node blocks (a, b), b >= a, of K, where B maps nodal positions to F
// (B_{iJ, 3a+k} = delta_ik dN_a/dX_J):
// K_{3a+i, 3b+k} += w sum_{J,L} dN_a/dX_J A_{iJ,kL} dN_b/dX_L. The blocks below the diagonal
// follow by symmetry (mirror_lower_blocks).
void add_material_stiffness(const hex8::ShapeGradients& G, const Mat9& A, double w,
                            ElementMatrix& K) {
  Eigen::Matrix<double, 9, 24> AB;  // column 3b + k: sum_L A_{., kL} dN_b/dX_L
  for (int b = 0; b < 8; ++b) {
    for (int k = 0; k < 3; ++k) {
      AB.col(3 * b + k) = A.col(k) * G(b, 0) + A.col(k + 3) * G(b, 1) + A.col(k + 6) * G(b, 2);
    }
  }
  for (int a = 0; a < 8; ++a) {
    const double w0 = w * G(a, 0), w1 = w * G(a, 1), w2 = w * G(a, 2);
    for (int b = a; b < 8; ++b) {
      K.block<3, 3>(3 * a, 3 * b).noalias() += w0 * AB.block<3, 3>(0, 3 * b) +
                                               w1 * AB.block<3, 3>(3, 3 * b) +
                                               w2 * AB.block<3, 3>(6, 3 * b);
    }
  }
}

// Completes a symmetric K of which the node blocks (a, b), b >= a, are filled.
void mirror_lower_blocks(ElementMatrix& K) {
  for (int a = 1; a < 8; ++a)
    for (int b = 0; b < a; ++b)
      K.block<3, 3>(3 * a, 3 * b) = K.block<3, 3>(3 * b, 3 * a).transpose();
}

// Adds w * (G P^T) to the force: f_{3a+i} += w sum_J P_iJ dN_a/dX_J.
void add_stress_force(const hex8::ShapeGradients& G, const Mat3& P, double w, ElementVector& f) {
  const Eigen::Matrix<double, 8, 3> nodal = G * P.transpose();
  for (int a = 0; a < 8; ++a) f.segment<3>(3 * a) += w * nodal.row(a).transpose();
}

// The residual path of an uncoupled material: the batch kernel (hex8_batch.hpp) on a batch of
// this element alone.
bool uncoupled_element_force(const ElementGeometry& geometry, const hex8::ElementCoords& x,
                             const UncoupledMaterial& material, Formulation formulation,
                             ElementResponse& r) {
  const ElementBatchGeometry batch = make_batch_geometry({&geometry, 1});
  BatchCoords coords;
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) coords[3 * a + i].lane.fill(x(a, i));
  ElementBatchResponse response;
  evaluate_batch_force(batch, coords, material, formulation, response);
  for (int k = 0; k < 24; ++k) r.force[k] = response.force[k].lane[0];
  r.energy = response.energy.lane[0];
  r.min_J = response.min_J.lane[0];
  return response.ok[0];
}

// The residual path of a material without the isochoric/volumetric split (standard
// formulation): P from the material at each Gauss point, f_ai += w dN_a/dX_J P_iJ.
bool coupled_element_force(const ElementGeometry& geometry, const hex8::ElementCoords& x,
                           const Material& material, ElementResponse& r) {
  double energy = 0.0;
  r.min_J = std::numeric_limits<double>::infinity();
  Eigen::Matrix<double, 8, 3> f = Eigen::Matrix<double, 8, 3>::Zero();  // row a: force on node a
  for (int q = 0; q < 8; ++q) {
    const Mat3 F = x.transpose() * geometry.dN_dX[q];
    const double J = F.determinant();
    r.min_J = std::min(r.min_J, J);
    if (!(J > 0.0)) return false;
    const PointResponse point = material.response(F, false);
    energy += geometry.weight[q] * point.energy;
    f.noalias() += geometry.dN_dX[q] * (geometry.weight[q] * point.stress.transpose());
  }
  r.energy = energy;
  for (int a = 0; a < 8; ++a) r.force.segment<3>(3 * a) = f.row(a).transpose();
  return true;
}

// The tangent path: force, energy and stiffness through the material's full response.
bool element_with_tangent(const ElementGeometry& geometry, const hex8::ElementCoords& x,
                          const Material& material, const UncoupledMaterial* uncoupled,
                          bool mean_dilatation, ElementResponse& r) {
  r.energy = 0.0;
  r.force.setZero();
  r.stiffness.setZero();
  r.min_J = std::numeric_limits<double>::infinity();

  // Mean dilatation: current volume v = sum J w, its gradient dv/dx and Hessian d2v/dx2.
  double v = 0.0;
  ElementVector dv = ElementVector::Zero();
  ElementMatrix d2v;
  if (mean_dilatation) d2v.setZero();

  for (int q = 0; q < 8; ++q) {
    const hex8::ShapeGradients& G = geometry.dN_dX[q];
    const double w = geometry.weight[q];
    const Mat3 F = x.transpose() * G;
    const double J = F.determinant();
    r.min_J = std::min(r.min_J, J);
    if (!(J > 0.0)) return false;

    const PointResponse point =
        mean_dilatation ? uncoupled->isochoric_response(F, true) : material.response(F, true);
    r.energy += w * point.energy;
    add_stress_force(G, point.stress, w, r.force);
    add_material_stiffness(G, point.tangent, w, r.stiffness);

    if (mean_dilatation) {
      // dJ/dx_{ai} = J g_{ai} and d2J/dx_{ai}dx_{bk} = J (g_ai g_bk - g_ak g_bi), with
      // g_a = F^{-T} dN_a/dX the spatial shape gradient (Bonet & Wood 2008, sec. 9.4).
      const Eigen::Matrix<double, 8, 3> g = G * F.inverse();
      const Eigen::Matrix<double, 3, 8> g_t = g.transpose();  // column a = g_a, so dof 3a + i
      const Eigen::Map<const ElementVector> g_flat(g_t.data());
      v += w * J;
      dv += (w * J) * g_flat;
      // Blocks (a, b), b > a only: the diagonal blocks vanish, the lower ones are the upper ones
      // transposed (mirror_lower_blocks).
      for (int a = 0; a < 8; ++a) {
        const Vec3 ga = (w * J) * g.row(a).transpose();
        for (int b = a + 1; b < 8; ++b) {
          const Vec3 gb = g.row(b).transpose();
          d2v.block<3, 3>(3 * a, 3 * b).noalias() += ga * gb.transpose() - gb * ga.transpose();
        }
      }
    }
  }

  if (mean_dilatation) {
    const double V = geometry.volume;
    const VolumetricResponse U = uncoupled->volumetric(v / V);
    r.energy += V * U.energy;
    r.force += U.first * dv;
    r.stiffness += (U.second / V) * (dv * dv.transpose()) + U.first * d2v;
  }
  mirror_lower_blocks(r.stiffness);
  return true;
}

}  // namespace

bool evaluate_element(const ElementGeometry& geometry, const hex8::ElementCoords& x,
                      const Material& material, Formulation formulation, bool want_stiffness,
                      ElementResponse& r) {
  const UncoupledMaterial* uncoupled = material.as_uncoupled();
  const bool mean_dilatation = formulation == Formulation::mean_dilatation;
  if (mean_dilatation && uncoupled == nullptr) {
    throw std::invalid_argument("mean dilatation needs a material split into W_iso + U(J); '" +
                                material.name() + "' is not");
  }
  if (want_stiffness)
    return element_with_tangent(geometry, x, material, uncoupled, mean_dilatation, r);
  if (uncoupled != nullptr) return uncoupled_element_force(geometry, x, *uncoupled, formulation, r);
  return coupled_element_force(geometry, x, material, r);
}

Eigen::Matrix<double, 8, 8> element_mass_pattern(const hex8::ElementCoords& X) {
  Eigen::Matrix<double, 8, 8> m = Eigen::Matrix<double, 8, 8>::Zero();
  for (const auto& qp : hex8::gauss_2x2x2()) {
    const hex8::ShapeValues N = hex8::values(qp.xi);
    const double w = qp.weight * hex8::jacobian(X, qp.xi).determinant();
    m.noalias() += w * (N * N.transpose());
  }
  return m;
}

Eigen::Matrix<double, 8, 1> element_shape_integrals(const ElementGeometry& geometry) {
  Eigen::Matrix<double, 8, 1> s = Eigen::Matrix<double, 8, 1>::Zero();
  const auto& rule = hex8::gauss_2x2x2();
  for (int q = 0; q < 8; ++q) s += geometry.weight[q] * hex8::values(rule[q].xi);
  return s;
}

}  // namespace tongue::fem
