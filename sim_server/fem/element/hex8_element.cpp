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
  for (int q = 0; q < 8; ++q) {
    g.weights[q] = g.weight[q];
    for (int J = 0; J < 3; ++J)
      for (int a = 0; a < 8; ++a) g.gradient_by_point[8 * J + a][q] = g.dN_dX[q](a, J);
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

// The residual path of an uncoupled material, all 8 Gauss points at once (one per lane of
// PointValues, so that every operation is a vector operation): F, adj F = J F^{-1} and J, the
// invariants, and the stress of add_isochoric (uncoupled_material.cpp) written out with
// s1 = 2 W1 J^{-2/3}, s2 = 2 W2 J^{-4/3}, T = F^{-T} = adj^T / J:
//   P_iso = (s1 + s2 I1) F - s2 F C - (s1 I1 / 3 + 2 s2 I2 / 3) T,
// plus the pressure term U' J T = U' adj^T: at U'(J) per point (standard) or U'(v / V) for the
// whole element (mean dilatation, where v = sum w J; its force d(V U)/dx = U' dv/dx with
// d(w J)/dx_a = w adj(F)^T dN_a/dX, Bonet & Wood 2008 sec. 9.4, so it needs no separate dv/dx).
bool uncoupled_element_force(const ElementGeometry& geometry, const hex8::ElementCoords& x,
                             const UncoupledMaterial& material, bool mean_dilatation,
                             ElementResponse& r) {
  using P8 = PointValues;
  const auto& G = geometry.gradient_by_point;
  P8 F[3][3];  // F_iJ = sum_a x_ai dN_a/dX_J
  for (int i = 0; i < 3; ++i) {
    for (int J = 0; J < 3; ++J) {
      P8 sum = x(0, i) * G[8 * J];
      for (int a = 1; a < 8; ++a) sum += x(a, i) * G[8 * J + a];
      F[i][J] = sum;
    }
  }
  P8 adj[3][3];  // adj(F) = det(F) F^{-1}
  adj[0][0] = F[1][1] * F[2][2] - F[1][2] * F[2][1];
  adj[0][1] = F[0][2] * F[2][1] - F[0][1] * F[2][2];
  adj[0][2] = F[0][1] * F[1][2] - F[0][2] * F[1][1];
  adj[1][0] = F[1][2] * F[2][0] - F[1][0] * F[2][2];
  adj[1][1] = F[0][0] * F[2][2] - F[0][2] * F[2][0];
  adj[1][2] = F[0][2] * F[1][0] - F[0][0] * F[1][2];
  adj[2][0] = F[1][0] * F[2][1] - F[1][1] * F[2][0];
  adj[2][1] = F[0][1] * F[2][0] - F[0][0] * F[2][1];
  adj[2][2] = F[0][0] * F[1][1] - F[0][1] * F[1][0];
  const P8 J = F[0][0] * adj[0][0] + F[0][1] * adj[1][0] + F[0][2] * adj[2][0];
  r.min_J = J.minCoeff();
  if (!(r.min_J > 0.0)) return false;

  P8 C[3][3];  // C = F^T F, symmetric
  for (int I = 0; I < 3; ++I) {
    for (int K = I; K < 3; ++K) {
      C[I][K] = F[0][I] * F[0][K] + F[1][I] * F[1][K] + F[2][I] * F[2][K];
      C[K][I] = C[I][K];
    }
  }
  const P8 I1 = C[0][0] + C[1][1] + C[2][2];
  const P8 CC = C[0][0] * C[0][0] + C[1][1] * C[1][1] + C[2][2] * C[2][2] +
                2.0 * (C[0][1] * C[0][1] + C[0][2] * C[0][2] + C[1][2] * C[1][2]);
  const P8 I2 = 0.5 * (I1 * I1 - CC);
  P8 a1, s1, s2, energy_density, pressure;
  const double v = (geometry.weights * J).sum();
  double energy = 0.0;
  if (mean_dilatation) {
    const VolumetricResponse U = material.volumetric(v / geometry.volume);
    energy += geometry.volume * U.energy;
    pressure.setConstant(U.first);
  }
  bool uses_I2 = false;
  for (int q = 0; q < 8; ++q) {
    const double c = std::cbrt(J[q]);
    const double j23 = 1.0 / (c * c);  // J^{-2/3}
    const InvariantDerivatives w = material.isochoric_derivatives(j23 * I1[q], j23 * j23 * I2[q]);
    s1[q] = 2.0 * w.d1 * j23;
    s2[q] = 2.0 * w.d2 * j23 * j23;
    uses_I2 = uses_I2 || w.d2 != 0.0;
    energy_density[q] = w.energy;
    if (!mean_dilatation) {
      const VolumetricResponse U = material.volumetric(J[q]);
      energy_density[q] += U.energy;
      pressure[q] = U.first;
    }
  }
  energy += (geometry.weights * energy_density).sum();
  // w P_iJ = w [(s1 + s2 I1) F - s2 F C - (t - p) adj^T], t = (s1 I1 + 2 s2 I2) / (3 J)
  const P8 wf = geometry.weights * (s1 + s2 * I1);
  const P8 wt = geometry.weights * ((s1 * I1 + 2.0 * s2 * I2) / (3.0 * J) - pressure);
  const P8 ws2 = geometry.weights * s2;
  P8 wP[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int K = 0; K < 3; ++K) {
      wP[i][K] = wf * F[i][K] - wt * adj[K][i];
      if (uses_I2) wP[i][K] -= ws2 * (F[i][0] * C[0][K] + F[i][1] * C[1][K] + F[i][2] * C[2][K]);
    }
  }
  // f_ai = sum over points and J of w P_iJ dN_a/dX_J.
  for (int a = 0; a < 8; ++a) {
    for (int i = 0; i < 3; ++i) {
      r.force[3 * a + i] = (wP[i][0] * G[a] + wP[i][1] * G[8 + a] + wP[i][2] * G[16 + a]).sum();
    }
  }
  r.energy = energy;
  return true;
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
  if (uncoupled != nullptr)
    return uncoupled_element_force(geometry, x, *uncoupled, mean_dilatation, r);
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
