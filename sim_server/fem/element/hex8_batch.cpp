#include "fem/element/hex8_batch.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

// The kernel computes on GCC vector types of 8 doubles. The helpers that take or return them are
// internal and always inlined into the kernel, so the argument-passing ABI of such types (which
// differs between SSE2 and AVX-512 code, what -Wpsabi warns about) never crosses a call.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace tongue::fem {

ElementBatchGeometry make_batch_geometry(std::span<const ElementGeometry> elements) {
  const int count = static_cast<int>(elements.size());
  if (count < 1 || count > kBatchLanes) {
    throw std::invalid_argument("element batch: 1 to " + std::to_string(kBatchLanes) +
                                " elements expected, got " + std::to_string(count));
  }
  ElementBatchGeometry b;
  b.count = count;
  for (int l = 0; l < kBatchLanes; ++l) {
    const ElementGeometry& g = elements[l < count ? l : 0];
    b.volume.lane[l] = g.volume;
    for (int q = 0; q < 8; ++q) {
      b.weight[q].lane[l] = g.weight[q];
      for (int J = 0; J < 3; ++J)
        for (int a = 0; a < 8; ++a) b.gradient[q][8 * J + a].lane[l] = g.dN_dX[q](a, J);
    }
  }
  return b;
}

namespace {

using Lanes = double __attribute__((vector_size(sizeof(LaneValues))));
using LaneMask = long long __attribute__((vector_size(sizeof(LaneValues))));  // -1 true, 0 false
static_assert(sizeof(Lanes) == kBatchLanes * sizeof(double));

[[gnu::always_inline]] inline Lanes load(const LaneValues& v) {
  Lanes r;
  std::memcpy(&r, v.lane.data(), sizeof r);
  return r;
}
[[gnu::always_inline]] inline Lanes load(const double* p) {
  Lanes r;
  std::memcpy(&r, p, sizeof r);
  return r;
}
[[gnu::always_inline]] inline void store(LaneValues& v, Lanes x) {
  std::memcpy(v.lane.data(), &x, sizeof x);
}
[[gnu::always_inline]] inline void store(double* p, Lanes x) {
  std::memcpy(p, &x, sizeof x);
}

// J^{-1/3} lane by lane. When every lane lies in [0.5, 2] (nearly incompressible tissue is
// within a few % of J = 1): a degree-4 polynomial start, interpolating J^{-1/3} at the Chebyshev
// nodes of that interval (relative error e <= 1.5e-3), then three Newton steps for y^{-3} = J,
// y <- y + y (1 - J y^3) / 3, each taking e to about 2 e^2: 4.5e-6, 4e-11, then round-off.
// Otherwise std::cbrt lane by lane.
[[gnu::always_inline]] inline Lanes inverse_cube_root(Lanes J) {
  const LaneMask inside = (J >= 0.5) & (J <= 2.0);
  bool all_inside = true;
  for (int l = 0; l < kBatchLanes; ++l) all_inside = all_inside && inside[l] != 0;
  if (!all_inside) {
    Lanes y;
    for (int l = 0; l < kBatchLanes; ++l) y[l] = 1.0 / std::cbrt(J[l]);
    return y;
  }
  Lanes y = 1.863911204977621 +
            J * (-1.7615233559419634 +
                 J * (1.3433317115723395 + J * (-0.5285183834495579 + J * 0.08176329728635946)));
  for (int step = 0; step < 3; ++step) y += y * (1.0 - J * (y * y * y)) * (1.0 / 3.0);
  return y;
}

// Per Gauss point, what the stress needs after the material's derivatives are known.
struct PointKinematics {
  Lanes F[3][3], adj[3][3], C[3][3];  // F, adj F = J F^{-1}, C = F^T F
  Lanes J, I1, I2, j23;               // det F, invariants of C, J^{-2/3}
};

// The stress of add_isochoric (uncoupled_material.cpp) written out with s1 = 2 W1 J^{-2/3},
// s2 = 2 W2 J^{-4/3}, T = F^{-T} = adj^T / J:
//   P_iso = (s1 + s2 I1) F - s2 F C - (s1 I1 / 3 + 2 s2 I2 / 3) T,
// plus the pressure term U' J T = U' adj^T: at U'(J) per point (standard) or U'(v / V) for the
// whole element (mean dilatation, where v = sum w J; its force d(V U)/dx = U' dv/dx with
// d(w J)/dx_a = w adj(F)^T dN_a/dX, Bonet & Wood 2008 sec. 9.4, so it needs no separate dv/dx).
// One function, compiled for AVX-512, AVX2 + FMA and baseline x86-64, the best one chosen when
// the program starts (GCC function multiversioning): the binary runs on any x86-64.
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void batch_force(
    const ElementBatchGeometry& g, const BatchCoords& coords, const UncoupledMaterial& material,
    bool mean_dilatation, ElementBatchResponse& r) {
  Lanes x[24];
  for (int k = 0; k < 24; ++k) x[k] = load(coords[k]);

  // Pass 1: kinematics at the 8 points; the invariants of C_bar for the material.
  PointKinematics p[8];
  alignas(64) double I1_bar[8 * kBatchLanes], I2_bar[8 * kBatchLanes];
  LaneMask ok = Lanes{} == 0.0;  // all true
  Lanes min_J = Lanes{} + std::numeric_limits<double>::infinity();
  Lanes v = Lanes{};  // current volume sum w J (mean dilatation)
  for (int q = 0; q < 8; ++q) {
    const auto& G = g.gradient[q];
    PointKinematics& k = p[q];
    auto& F = k.F;
    for (int i = 0; i < 3; ++i) {
      for (int J = 0; J < 3; ++J) {
        Lanes sum = x[i] * load(G[8 * J]);
        for (int a = 1; a < 8; ++a) sum += x[3 * a + i] * load(G[8 * J + a]);
        F[i][J] = sum;
      }
    }
    auto& adj = k.adj;
    adj[0][0] = F[1][1] * F[2][2] - F[1][2] * F[2][1];
    adj[0][1] = F[0][2] * F[2][1] - F[0][1] * F[2][2];
    adj[0][2] = F[0][1] * F[1][2] - F[0][2] * F[1][1];
    adj[1][0] = F[1][2] * F[2][0] - F[1][0] * F[2][2];
    adj[1][1] = F[0][0] * F[2][2] - F[0][2] * F[2][0];
    adj[1][2] = F[0][2] * F[1][0] - F[0][0] * F[1][2];
    adj[2][0] = F[1][0] * F[2][1] - F[1][1] * F[2][0];
    adj[2][1] = F[0][1] * F[2][0] - F[0][0] * F[2][1];
    adj[2][2] = F[0][0] * F[1][1] - F[0][1] * F[1][0];
    k.J = F[0][0] * adj[0][0] + F[0][1] * adj[1][0] + F[0][2] * adj[2][0];
    ok &= k.J > 0.0;  // false for NaN too
    min_J = k.J < min_J ? k.J : min_J;
    v += load(g.weight[q]) * k.J;

    auto& C = k.C;
    for (int I = 0; I < 3; ++I) {
      for (int K = I; K < 3; ++K) {
        C[I][K] = F[0][I] * F[0][K] + F[1][I] * F[1][K] + F[2][I] * F[2][K];
        C[K][I] = C[I][K];
      }
    }
    k.I1 = C[0][0] + C[1][1] + C[2][2];
    const Lanes CC = C[0][0] * C[0][0] + C[1][1] * C[1][1] + C[2][2] * C[2][2] +
                     2.0 * (C[0][1] * C[0][1] + C[0][2] * C[0][2] + C[1][2] * C[1][2]);
    k.I2 = 0.5 * (k.I1 * k.I1 - CC);
    const Lanes y = inverse_cube_root(k.J);
    k.j23 = y * y;
    store(I1_bar + kBatchLanes * q, k.j23 * k.I1);
    store(I2_bar + kBatchLanes * q, k.j23 * k.j23 * k.I2);
  }

  alignas(64) double W[8 * kBatchLanes], W1[8 * kBatchLanes], W2[8 * kBatchLanes];
  material.isochoric_first_derivatives(8 * kBatchLanes, I1_bar, I2_bar, W, W1, W2);
  bool uses_I2 = false;
  for (double d2 : W2) uses_I2 = uses_I2 || d2 != 0.0;

  // The volumetric part: per element (mean dilatation) or per point (standard).
  alignas(64) double U[8 * kBatchLanes], dU[8 * kBatchLanes];
  Lanes energy = Lanes{};
  if (mean_dilatation) {
    const Lanes V = load(g.volume);
    for (int l = 0; l < kBatchLanes; ++l) {
      const VolumetricResponse response = material.volumetric(v[l] / V[l]);
      energy[l] = V[l] * response.energy;
      for (int q = 0; q < 8; ++q) {
        U[kBatchLanes * q + l] = 0.0;
        dU[kBatchLanes * q + l] = response.first;
      }
    }
  } else {
    for (int q = 0; q < 8; ++q) {
      for (int l = 0; l < kBatchLanes; ++l) {
        const VolumetricResponse response = material.volumetric(p[q].J[l]);
        U[kBatchLanes * q + l] = response.energy;
        dU[kBatchLanes * q + l] = response.first;
      }
    }
  }

  // Pass 2: w P_iJ = w [(s1 + s2 I1) F - s2 F C - (t - p) adj^T], t = (s1 I1 + 2 s2 I2) / (3 J),
  // and f_ai = sum over points and J of w P_iJ dN_a/dX_J.
  Lanes f[24];
  for (Lanes& fk : f) fk = Lanes{};
  for (int q = 0; q < 8; ++q) {
    const PointKinematics& k = p[q];
    const auto& G = g.gradient[q];
    const Lanes w = load(g.weight[q]);
    const Lanes s1 = 2.0 * load(W1 + kBatchLanes * q) * k.j23;
    const Lanes s2 = 2.0 * load(W2 + kBatchLanes * q) * k.j23 * k.j23;
    energy += w * (load(W + kBatchLanes * q) + load(U + kBatchLanes * q));
    const Lanes wf = w * (s1 + s2 * k.I1);
    const Lanes wt = w * ((s1 * k.I1 + 2.0 * s2 * k.I2) / (3.0 * k.J) - load(dU + kBatchLanes * q));
    const Lanes ws2 = w * s2;
    Lanes wP[3][3];
    for (int i = 0; i < 3; ++i) {
      for (int K = 0; K < 3; ++K) {
        wP[i][K] = wf * k.F[i][K] - wt * k.adj[K][i];
        if (uses_I2) {
          wP[i][K] -= ws2 * (k.F[i][0] * k.C[0][K] + k.F[i][1] * k.C[1][K] + k.F[i][2] * k.C[2][K]);
        }
      }
    }
    for (int a = 0; a < 8; ++a) {
      const Lanes g0 = load(G[a]), g1 = load(G[8 + a]), g2 = load(G[16 + a]);
      for (int i = 0; i < 3; ++i) f[3 * a + i] += wP[i][0] * g0 + wP[i][1] * g1 + wP[i][2] * g2;
    }
  }

  for (int k = 0; k < 24; ++k) store(r.force[k], f[k]);
  store(r.energy, energy);
  store(r.min_J, min_J);
  for (int l = 0; l < kBatchLanes; ++l) r.ok[l] = ok[l] != 0;
}

}  // namespace

void evaluate_batch_force(const ElementBatchGeometry& geometry, const BatchCoords& x,
                          const UncoupledMaterial& material, Formulation formulation,
                          ElementBatchResponse& response) {
  batch_force(geometry, x, material, formulation == Formulation::mean_dilatation, response);
}

}  // namespace tongue::fem
