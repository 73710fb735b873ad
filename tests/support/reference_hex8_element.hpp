#pragma once
// The hexahedron as it was evaluated before the fast kernels (docs/speed.md): the straightforward
// loop over Gauss points through Material::response, kept only as a reference that the optimized
// element (fem/element/hex8_element.cpp, hex8_batch.cpp) must reproduce to round-off.
#include <algorithm>
#include <limits>
#include <stdexcept>

#include "fem/element/hex8_element.hpp"

namespace tongue::testing {

using namespace tongue::fem;  // NOLINT: a test-only header in its own namespace

// Adds w * B^T A B to K, where B maps nodal positions to F (B_{iJ, 3a+k} = delta_ik dN_a/dX_J):
// K_{3a+i, 3b+k} += w sum_{J,L} dN_a/dX_J A_{iJ,kL} dN_b/dX_L.
inline void add_material_stiffness(const hex8::ShapeGradients& G, const Mat9& A, double w,
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
inline void add_stress_force(const hex8::ShapeGradients& G, const Mat3& P, double w,
                             ElementVector& f) {
  const Eigen::Matrix<double, 8, 3> nodal = G * P.transpose();
  for (int a = 0; a < 8; ++a) f.segment<3>(3 * a) += w * nodal.row(a).transpose();
}

inline bool reference_evaluate_element(const ElementGeometry& geometry,
                                       const hex8::ElementCoords& x, const Material& material,
                                       Formulation formulation, bool want_stiffness,
                                       ElementResponse& r) {
  const UncoupledMaterial* uncoupled = material.as_uncoupled();
  const bool mean_dilatation = formulation == Formulation::mean_dilatation;
  if (mean_dilatation && uncoupled == nullptr) {
    throw std::invalid_argument("mean dilatation needs a material split into W_iso + U(J); '" +
                                material.name() + "' is not");
  }
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

}  // namespace tongue::testing
