#include "fem/element/hex8_element.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>

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

// Adds w * B^T A B to K, where B maps nodal positions to F (B_{iJ, 3a+k} = delta_ik dN_a/dX_J):
// K_{3a+i, 3b+k} += w sum_{J,L} dN_a/dX_J A_{iJ,kL} dN_b/dX_L.
void add_material_stiffness(const hex8::ShapeGradients& G, const Mat9& A, double w,
                            ElementMatrix& K) {
  Eigen::Matrix<double, 9, 24> AB;
  for (int b = 0; b < 8; ++b) {
    for (int k = 0; k < 3; ++k) {
      AB.col(3 * b + k) = A.col(k) * G(b, 0) + A.col(k + 3) * G(b, 1) + A.col(k + 6) * G(b, 2);
    }
  }
  for (int a = 0; a < 8; ++a) {
    for (int i = 0; i < 3; ++i) {
      K.row(3 * a + i).noalias() +=
          w * (G(a, 0) * AB.row(i) + G(a, 1) * AB.row(i + 3) + G(a, 2) * AB.row(i + 6));
    }
  }
}

// Adds w * (G P^T) to the force: f_{3a+i} += w sum_J P_iJ dN_a/dX_J.
void add_stress_force(const hex8::ShapeGradients& G, const Mat3& P, double w, ElementVector& f) {
  const Eigen::Matrix<double, 8, 3> nodal = G * P.transpose();
  for (int a = 0; a < 8; ++a) f.segment<3>(3 * a) += w * nodal.row(a).transpose();
}

// adj(F) = det(F) F^{-1}, the transposed cofactor matrix, written out.
Mat3 adjugate(const Mat3& F) {
  Mat3 a;
  a(0, 0) = F(1, 1) * F(2, 2) - F(1, 2) * F(2, 1);
  a(0, 1) = F(0, 2) * F(2, 1) - F(0, 1) * F(2, 2);
  a(0, 2) = F(0, 1) * F(1, 2) - F(0, 2) * F(1, 1);
  a(1, 0) = F(1, 2) * F(2, 0) - F(1, 0) * F(2, 2);
  a(1, 1) = F(0, 0) * F(2, 2) - F(0, 2) * F(2, 0);
  a(1, 2) = F(0, 2) * F(1, 0) - F(0, 0) * F(1, 2);
  a(2, 0) = F(1, 0) * F(2, 1) - F(1, 1) * F(2, 0);
  a(2, 1) = F(0, 1) * F(2, 0) - F(0, 0) * F(2, 1);
  a(2, 2) = F(0, 0) * F(1, 1) - F(0, 1) * F(1, 0);
  return a;
}

// The residual path: force and energy only. Two passes over the Gauss points: the first finds
// F, J and (mean dilatation) the element's volume v, hence the pressure factor U'(v / V); the
// second adds P^T = P_iso^T + U' J F^{-1} = P_iso^T + U' adj(F) per point, so the volumetric
// force needs no separate dv/dx (d(w J)/dx_a = w adj(F)^T dN_a/dX, Bonet & Wood 2008 sec. 9.4).
bool element_force(const ElementGeometry& geometry, const hex8::ElementCoords& x,
                   const Material& material, const UncoupledMaterial* uncoupled,
                   bool mean_dilatation, ElementResponse& r) {
  std::array<Mat3, 8> F;
  std::array<Mat3, 8> adj;
  std::array<double, 8> J;
  double v = 0.0;
  double min_J = std::numeric_limits<double>::infinity();
  for (int q = 0; q < 8; ++q) {
    F[q].noalias() = x.transpose() * geometry.dN_dX[q];
    adj[q] = adjugate(F[q]);
    J[q] = F[q].row(0).dot(adj[q].col(0));
    min_J = std::min(min_J, J[q]);
    v += geometry.weight[q] * J[q];
  }
  r.min_J = min_J;
  if (!(min_J > 0.0)) return false;

  double energy = 0.0;
  double pressure = 0.0;  // U'(J_bar) for mean dilatation
  if (mean_dilatation) {
    const VolumetricResponse U = uncoupled->volumetric(v / geometry.volume);
    energy += geometry.volume * U.energy;
    pressure = U.first;
  }
  Eigen::Matrix<double, 8, 3> f = Eigen::Matrix<double, 8, 3>::Zero();  // row a: force on node a
  for (int q = 0; q < 8; ++q) {
    const double w = geometry.weight[q];
    Mat3 Pt;  // P^T
    if (uncoupled != nullptr) {
      Mat3 P;
      energy += w * uncoupled->isochoric_stress(F[q], J[q], adj[q], P);
      double p = pressure;
      if (!mean_dilatation) {
        const VolumetricResponse U = uncoupled->volumetric(J[q]);
        energy += w * U.energy;
        p = U.first;
      }
      Pt.noalias() = P.transpose() + p * adj[q];
    } else {
      const PointResponse point = material.response(F[q], false);
      energy += w * point.energy;
      Pt = point.stress.transpose();
    }
    f.noalias() += geometry.dN_dX[q] * (w * Pt);  // f_ai += w dN_a/dX_J P_iJ
  }
  r.energy = energy;
  for (int a = 0; a < 8; ++a) r.force.segment<3>(3 * a) = f.row(a).transpose();
  return true;
}

// The tangent path: force, energy and stiffness through the material's full response.
bool element_with_tangent(const ElementGeometry& geometry, const hex8::ElementCoords& x,
                          const Material& material, const UncoupledMaterial* uncoupled,
                          bool mean_dilatation, ElementResponse& r) {
  const bool want_stiffness = true;
  r.energy = 0.0;
  r.force.setZero();
  if (want_stiffness) r.stiffness.setZero();
  r.min_J = std::numeric_limits<double>::infinity();

  // Mean dilatation: current volume v = sum J w, its gradient dv/dx and Hessian d2v/dx2.
  double v = 0.0;
  ElementVector dv = ElementVector::Zero();
  ElementMatrix d2v;
  if (mean_dilatation && want_stiffness) d2v.setZero();

  for (int q = 0; q < 8; ++q) {
    const hex8::ShapeGradients& G = geometry.dN_dX[q];
    const double w = geometry.weight[q];
    const Mat3 F = x.transpose() * G;
    const double J = F.determinant();
    r.min_J = std::min(r.min_J, J);
    if (!(J > 0.0)) return false;

    const PointResponse point = mean_dilatation ? uncoupled->isochoric_response(F, want_stiffness)
                                                : material.response(F, want_stiffness);
    r.energy += w * point.energy;
    add_stress_force(G, point.stress, w, r.force);
    if (want_stiffness) add_material_stiffness(G, point.tangent, w, r.stiffness);

    if (mean_dilatation) {
      // dJ/dx_{ai} = J g_{ai} and d2J/dx_{ai}dx_{bk} = J (g_ai g_bk - g_ak g_bi), with
      // g_a = F^{-T} dN_a/dX the spatial shape gradient (Bonet & Wood 2008, sec. 9.4).
      const Eigen::Matrix<double, 8, 3> g = G * F.inverse();
      const Eigen::Matrix<double, 3, 8> g_t = g.transpose();  // column a = g_a, so dof 3a + i
      const Eigen::Map<const ElementVector> g_flat(g_t.data());
      v += w * J;
      dv += (w * J) * g_flat;
      if (want_stiffness) {
        for (int a = 0; a < 8; ++a) {
          for (int b = 0; b < 8; ++b) {
            const Eigen::RowVector3d ga = g.row(a), gb = g.row(b);
            d2v.block<3, 3>(3 * a, 3 * b) += (w * J) * (ga.transpose() * gb - gb.transpose() * ga);
          }
        }
      }
    }
  }

  if (mean_dilatation) {
    const double V = geometry.volume;
    const VolumetricResponse U = uncoupled->volumetric(v / V);
    r.energy += V * U.energy;
    r.force += U.first * dv;
    if (want_stiffness) r.stiffness += (U.second / V) * (dv * dv.transpose()) + U.first * d2v;
  }
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
  return want_stiffness ? element_with_tangent(geometry, x, material, uncoupled, mean_dilatation, r)
                        : element_force(geometry, x, material, uncoupled, mean_dilatation, r);
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
