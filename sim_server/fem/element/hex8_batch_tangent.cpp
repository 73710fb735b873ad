#include "fem/element/hex8_batch_tangent.hpp"

#include <limits>
#include <stdexcept>

#include "fem/element/hex8_batch_lanes.hpp"

namespace tongue::fem {
namespace {

// What forms w A at a Gauss point besides F and C (see lanes_tangent).
template <int N>
struct TangentTerms {
  Lanes<N> T[3][3];                       // F^{-T}
  Lanes<N> Mff, Mft, Mtt, Mfc, Mtc, Mcc;  // w M over (f, t, c)
  Lanes<N> cT, cI, c2;                    // w cT, w cI, and w cF = w cC = w cb
};

// w A, all 81 entries (the 45 of the upper triangle, mirrored). Without I2 (UsesI2 false) the
// terms in c, b and the F cross term vanish and are skipped.
template <int N, bool UsesI2>
[[gnu::always_inline]] inline void form_tangent(const PointKinematics<N>& k,
                                                const Lanes<N> (&FC)[3][3],
                                                const TangentTerms<N>& t, Lanes<N> (&A)[9][9]) {
  using V = Lanes<N>;
  const auto& F = k.F;
  const auto& T = t.T;
  // W_m = sum_n M_mn v_n over the flat index p = i + 3J.
  V Wf[9], Wt[9], Wc[9];
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) {
#pragma GCC unroll 3
    for (int J = 0; J < 3; ++J) {
      const int p = i + 3 * J;
      Wf[p] = t.Mff * F[i][J] + t.Mft * T[i][J];
      Wt[p] = t.Mft * F[i][J] + t.Mtt * T[i][J];
      if constexpr (UsesI2) {
        Wf[p] += t.Mfc * FC[i][J];
        Wt[p] += t.Mtc * FC[i][J];
        Wc[p] = t.Mfc * F[i][J] + t.Mtc * T[i][J] + t.Mcc * FC[i][J];
      }
    }
  }
  V b[3][3];  // F F^T
  if constexpr (UsesI2) {
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i)
#pragma GCC unroll 3
      for (int m = i; m < 3; ++m)
        b[i][m] = b[m][i] = F[i][0] * F[m][0] + F[i][1] * F[m][1] + F[i][2] * F[m][2];
  }
#pragma GCC unroll 3
  for (int J = 0; J < 3; ++J) {
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) {
      const int p = i + 3 * J;
#pragma GCC unroll 3
      for (int L = 0; L < 3; ++L) {
#pragma GCC unroll 3
        for (int m = 0; m < 3; ++m) {
          const int q = m + 3 * L;
          if (q < p) continue;
          V a = F[i][J] * Wf[q] + T[i][J] * Wt[q] + t.cT * T[i][L] * T[m][J];
          if constexpr (UsesI2) {
            a += FC[i][J] * Wc[q] + t.c2 * F[i][L] * F[m][J];
            if (i == m) a += t.c2 * k.C[J][L];
            if (J == L) a += t.c2 * b[i][m];
          }
          if (p == q) a += t.cI;
          A[p][q] = A[q][p] = a;
        }
      }
    }
  }
}

// K_{3a+i, 3b+k} += sum_JL G[J][a] A[i + 3J][k + 3L] G[L][b] for the upper node blocks, K at the
// kernel's lane o of ElementBatchTangent::stiffness (entry s at K + kBatchLanes s). Column block
// b of A B is formed once, in registers, and serves the blocks (a, b), a <= b.
template <int N>
[[gnu::always_inline]] inline void add_node_blocks(const Lanes<N> (&A)[9][9],
                                                   const Lanes<N> (&G)[3][8], double* K) {
  using V = Lanes<N>;
  for (int nb = 0; nb < 8; ++nb) {
    V AB[9][3];
#pragma GCC unroll 9
    for (int p = 0; p < 9; ++p)
#pragma GCC unroll 3
      for (int m = 0; m < 3; ++m)
        AB[p][m] = A[p][m] * G[0][nb] + A[p][m + 3] * G[1][nb] + A[p][m + 6] * G[2][nb];
    for (int na = 0; na <= nb; ++na) {
      double* block = K + kBatchLanes * 9 * upper_block(na, nb);
#pragma GCC unroll 3
      for (int i = 0; i < 3; ++i) {
#pragma GCC unroll 3
        for (int m = 0; m < 3; ++m) {
          double* entry = block + kBatchLanes * (3 * i + m);
          store<N>(entry, load<N>(entry) + G[0][na] * AB[i][m] + G[1][na] * AB[i + 3][m] +
                              G[2][na] * AB[i + 6][m]);
        }
      }
    }
  }
}

// Lanes o .. o + N - 1 of the batch, with vectors of N doubles.
//
// Per Gauss point the 9 x 9 tangent A = d2W/dF dF (index i + 3J, as types.hpp) is formed from
// the invariant derivatives with the terms of add_isochoric (uncoupled_material.cpp; Holzapfel
// 2000, sec. 6.4), grouped: with a1 = J^{-2/3}, a2 = J^{-4/3}, s1 = W1 a1, s2 = W2 a2,
// T = F^{-T} and the three tensors f = F, t = T, c = F C,
//   dI1b = 2 a1 f - (2/3) a1 I1 t,   dI2b = 2 a2 I1 f - (4/3) a2 I2 t - 2 a2 c,
// every rank-1 and symmetric rank-2 term lies in their span, so that
//   A = sum_mn M_mn v_m (x) v_n  (v = f, t, c; M symmetric 3 x 3)
//     + cT T_iL T_kJ + cF F_iL F_kJ + cI d_ik d_JL + cC d_ik C_JL + cb b_ik d_JL,  b = F F^T,
// plus the volumetric part U'' J^2 t (x) t + U' J (t (x) t - T_iL T_kJ). Then
// K_{3a+i, 3b+k} += w sum_JL dN_a/dX_J A_{iJ,kL} dN_b/dX_L over the points, upper node blocks.
//
// Mean dilatation: V U(v / V) with v = sum w J has the Hessian U' d2v + (U'' / V) dv (x) dv
// (Bonet & Wood 2008, sec. 9.4), and d2v = sum w B^T d2J/dF2 B with d2J/dF2 = J (t (x) t -
// T_iL T_kJ): the U' part is the standard volumetric term at the element's U', the U'' part one
// rank-1 update per element, dv_{3a+i} = sum w (adj(F)^T dN_a/dX)_i.
template <int N>
[[gnu::always_inline]] inline void lanes_tangent(const ElementBatchGeometry& g,
                                                 const BatchCoords& coords,
                                                 const UncoupledMaterial& material,
                                                 bool mean_dilatation, int o,
                                                 ElementBatchTangent& result) {
  using V = Lanes<N>;
  ElementBatchResponse& r = result.response;
  V x[24];
  for (int k = 0; k < 24; ++k) x[k] = load<N>(&coords[k].lane[o]);

  // Pass 1: kinematics at the 8 points; the invariants of C_bar for the material.
  PointKinematics<N> p[8];
  alignas(64) double I1_bar[8 * N], I2_bar[8 * N];
  auto ok = V{} == 0.0;  // all true
  V min_J = V{} + std::numeric_limits<double>::infinity();
  V v = V{};  // current volume sum w J (mean dilatation)
  for (int q = 0; q < 8; ++q) {
    PointKinematics<N>& k = p[q];
    point_kinematics<N>(g, x, q, o, k);
    ok &= k.J > 0.0;  // false for NaN too
    min_J = k.J < min_J ? k.J : min_J;
    v += load<N>(&g.weight[q].lane[o]) * k.J;
    store<N>(I1_bar + N * q, k.j23 * k.I1);
    store<N>(I2_bar + N * q, k.j23 * k.j23 * k.I2);
  }

  alignas(64) double W0[8 * N], W1[8 * N], W2[8 * N], W11[8 * N], W12[8 * N], W22[8 * N];
  material.isochoric_second_derivatives(8 * N, I1_bar, I2_bar, W0, W1, W2, W11, W12, W22);
  bool uses_I2 = false;
  for (int i = 0; i < 8 * N; ++i)
    uses_I2 = uses_I2 || W2[i] != 0.0 || W12[i] != 0.0 || W22[i] != 0.0;

  // The volumetric part: U' per element and U'' / V for its rank-1 term (mean dilatation), or
  // U, U', U'' per point (standard).
  alignas(64) double U[8 * N], dU[8 * N], ddU[8 * N];
  V energy = V{}, element_ddU = V{};
  if (mean_dilatation) {
    const V V0 = load<N>(&g.volume.lane[o]);
    for (int l = 0; l < N; ++l) {
      const VolumetricResponse response = material.volumetric(v[l] / V0[l]);
      energy[l] = V0[l] * response.energy;
      element_ddU[l] = response.second / V0[l];
      for (int q = 0; q < 8; ++q) {
        U[N * q + l] = 0.0;
        dU[N * q + l] = response.first;
        ddU[N * q + l] = 0.0;
      }
    }
  } else {
    for (int q = 0; q < 8; ++q) {
      for (int l = 0; l < N; ++l) {
        const VolumetricResponse response = material.volumetric(p[q].J[l]);
        U[N * q + l] = response.energy;
        dU[N * q + l] = response.first;
        ddU[N * q + l] = response.second;
      }
    }
  }

  // Pass 2: force as in the residual kernel, tangent as above.
  V f[24], dv[24];
  for (int k = 0; k < 24; ++k) f[k] = dv[k] = V{};
  for (int s = 0; s < 9 * kUpperBlocks; ++s) store<N>(&result.stiffness[s].lane[o], V{});
  for (int q = 0; q < 8; ++q) {
    const PointKinematics<N>& k = p[q];
    const auto& F = k.F;
    V G[3][8];  // G[J][a] = dN_a/dX_J
    for (int J = 0; J < 3; ++J)
      for (int a = 0; a < 8; ++a) G[J][a] = load<N>(&g.gradient[q][8 * J + a].lane[o]);
    const V w = load<N>(&g.weight[q].lane[o]);
    const V a1 = k.j23, a2 = a1 * a1;
    const V s1 = load<N>(W1 + N * q) * a1, s2 = load<N>(W2 + N * q) * a2;
    const V pressure = load<N>(dU + N * q);  // U'
    energy += w * (load<N>(W0 + N * q) + load<N>(U + N * q));

    V FC[3][3];
    if (uses_I2) {
      for (int i = 0; i < 3; ++i)
        for (int L = 0; L < 3; ++L)
          FC[i][L] = F[i][0] * k.C[0][L] + F[i][1] * k.C[1][L] + F[i][2] * k.C[2][L];
    }

    // w P = w [2 (s1 + s2 I1) F - 2 s2 F C - ((2 s1 I1 + 4 s2 I2) / (3 J) - U') adj^T].
    {
      const V wf = w * (2.0 * (s1 + s2 * k.I1));
      const V wt = w * ((2.0 * s1 * k.I1 + 4.0 * s2 * k.I2) / (3.0 * k.J) - pressure);
      V wP[3][3];
      for (int i = 0; i < 3; ++i) {
        for (int K = 0; K < 3; ++K) {
          wP[i][K] = wf * F[i][K] - wt * k.adj[K][i];
          if (uses_I2) wP[i][K] -= (2.0 * w * s2) * FC[i][K];
        }
      }
      for (int a = 0; a < 8; ++a)
        for (int i = 0; i < 3; ++i)
          f[3 * a + i] += wP[i][0] * G[0][a] + wP[i][1] * G[1][a] + wP[i][2] * G[2][a];
    }
    if (mean_dilatation) {
      for (int a = 0; a < 8; ++a)
        for (int i = 0; i < 3; ++i)
          dv[3 * a + i] +=
              w * (k.adj[0][i] * G[0][a] + k.adj[1][i] * G[1][a] + k.adj[2][i] * G[2][a]);
    }

    // The coefficients of A, times w.
    TangentTerms<N> t;
    const V inv_J = 1.0 / k.J;
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) t.T[i][J] = k.adj[J][i] * inv_J;
    const V d11 = load<N>(W11 + N * q);
    const V uf = 2.0 * a1, ut = (-2.0 / 3.0) * a1 * k.I1;  // dI1b in (f, t)
    V Mff = d11 * uf * uf + 4.0 * s2;
    V Mft = d11 * uf * ut - (4.0 / 3.0) * s1;
    V Mtt = d11 * ut * ut + (4.0 / 9.0) * s1 * k.I1 + k.J * (load<N>(ddU + N * q) * k.J + pressure);
    t.cT = w * ((2.0 / 3.0) * s1 * k.I1 + (4.0 / 3.0) * s2 * k.I2 - pressure * k.J);
    t.cI = w * (2.0 * (s1 + s2 * k.I1));
    V A[9][9];
    if (uses_I2) {
      const V d12 = load<N>(W12 + N * q), d22 = load<N>(W22 + N * q);
      const V vf = 2.0 * a2 * k.I1, vt = (-4.0 / 3.0) * a2 * k.I2, vc = -2.0 * a2;  // dI2b
      Mff += 2.0 * d12 * uf * vf + d22 * vf * vf;
      Mft += d12 * (uf * vt + ut * vf) + d22 * vf * vt - (8.0 / 3.0) * s2 * k.I1;
      Mtt += 2.0 * d12 * ut * vt + d22 * vt * vt + (16.0 / 9.0) * s2 * k.I2;
      t.Mfc = w * (d12 * uf * vc + d22 * vf * vc);
      t.Mtc = w * (d12 * ut * vc + d22 * vt * vc + (8.0 / 3.0) * s2);
      t.Mcc = w * (d22 * vc * vc);
      t.c2 = -2.0 * w * s2;
      t.Mff = w * Mff, t.Mft = w * Mft, t.Mtt = w * Mtt;
      form_tangent<N, true>(k, FC, t, A);
    } else {
      t.Mff = w * Mff, t.Mft = w * Mft, t.Mtt = w * Mtt;
      form_tangent<N, false>(k, FC, t, A);
    }
    add_node_blocks<N>(A, G, &result.stiffness[0].lane[o]);
  }

  if (mean_dilatation) {
    for (int na = 0; na < 8; ++na) {
      for (int nb = na; nb < 8; ++nb) {
        double* K = &result.stiffness[9 * upper_block(na, nb)].lane[o];
        for (int i = 0; i < 3; ++i) {
          const V scaled = element_ddU * dv[3 * na + i];
          for (int kk = 0; kk < 3; ++kk) {
            double* entry = K + kBatchLanes * (3 * i + kk);
            store<N>(entry, load<N>(entry) + scaled * dv[3 * nb + kk]);
          }
        }
      }
    }
  }

  for (int k = 0; k < 24; ++k) store<N>(&r.force[k].lane[o], f[k]);
  store<N>(&r.energy.lane[o], energy);
  store<N>(&r.min_J.lane[o], min_J);
  for (int l = 0; l < N; ++l) r.ok[o + l] = ok[l] != 0;
}

template <int N>
[[gnu::always_inline]] inline void lanes_tangent_all(const ElementBatchGeometry& g,
                                                     const BatchCoords& coords,
                                                     const UncoupledMaterial& material,
                                                     bool mean_dilatation,
                                                     ElementBatchTangent& result) {
  static_assert(kBatchLanes % N == 0);
  for (int o = 0; o < kBatchLanes; o += N)
    lanes_tangent<N>(g, coords, material, mean_dilatation, o, result);
}

// One kernel per instruction set, as for the residual (hex8_batch.cpp).
__attribute__((target("arch=x86-64-v4"))) void avx512_tangent(const ElementBatchGeometry& g,
                                                              const BatchCoords& coords,
                                                              const UncoupledMaterial& material,
                                                              bool mean_dilatation,
                                                              ElementBatchTangent& result) {
  lanes_tangent_all<8>(g, coords, material, mean_dilatation, result);
}
__attribute__((target("arch=x86-64-v3"))) void avx2_tangent(const ElementBatchGeometry& g,
                                                            const BatchCoords& coords,
                                                            const UncoupledMaterial& material,
                                                            bool mean_dilatation,
                                                            ElementBatchTangent& result) {
  lanes_tangent_all<4>(g, coords, material, mean_dilatation, result);
}
void sse2_tangent(const ElementBatchGeometry& g, const BatchCoords& coords,
                  const UncoupledMaterial& material, bool mean_dilatation,
                  ElementBatchTangent& result) {
  lanes_tangent_all<2>(g, coords, material, mean_dilatation, result);
}

}  // namespace

void evaluate_batch_tangent(const ElementBatchGeometry& geometry, const BatchCoords& x,
                            const UncoupledMaterial& material, Formulation formulation,
                            ElementBatchTangent& result, SimdLevel level) {
  if (level > best_simd_level())
    throw std::invalid_argument("element batch: this CPU does not run the requested kernel");
  const bool mean_dilatation = formulation == Formulation::mean_dilatation;
  switch (level) {
    case SimdLevel::avx512:
      return avx512_tangent(geometry, x, material, mean_dilatation, result);
    case SimdLevel::avx2:
      return avx2_tangent(geometry, x, material, mean_dilatation, result);
    case SimdLevel::sse2:
      return sse2_tangent(geometry, x, material, mean_dilatation, result);
  }
}

ElementMatrix lane_stiffness(const ElementBatchTangent& result, int lane) {
  ElementMatrix K;
  for (int a = 0; a < 8; ++a) {
    for (int b = a; b < 8; ++b) {
      const int block = 9 * upper_block(a, b);
      for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k) {
          const double value = result.stiffness[block + 3 * i + k].lane[lane];
          K(3 * a + i, 3 * b + k) = value;
          if (b != a) K(3 * b + k, 3 * a + i) = value;
        }
      }
    }
  }
  return K;
}

}  // namespace tongue::fem
