#include "fem/element/hex8_batch.hpp"

#include <limits>
#include <stdexcept>
#include <string>

#include "fem/element/hex8_batch_lanes.hpp"

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

// Lanes o .. o + N - 1 of the batch, with vectors of N doubles. The stress of add_isochoric
// (uncoupled_material.cpp) written out with s1 = 2 W1 J^{-2/3}, s2 = 2 W2 J^{-4/3},
// T = F^{-T} = adj^T / J:
//   P_iso = (s1 + s2 I1) F - s2 F C - (s1 I1 / 3 + 2 s2 I2 / 3) T,
// plus the pressure term U' J T = U' adj^T: at U'(J) per point (standard) or U'(v / V) for the
// whole element (mean dilatation, where v = sum w J; its force d(V U)/dx = U' dv/dx with
// d(w J)/dx_a = w adj(F)^T dN_a/dX, Bonet & Wood 2008 sec. 9.4, so it needs no separate dv/dx).
template <int N>
[[gnu::always_inline]] inline void lanes_force(const ElementBatchGeometry& g,
                                               const BatchCoords& coords,
                                               const UncoupledMaterial& material,
                                               bool mean_dilatation, int o,
                                               ElementBatchResponse& r) {
  using V = Lanes<N>;
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

  alignas(64) double W0[8 * N], W1[8 * N], W2[8 * N];
  material.isochoric_first_derivatives(8 * N, I1_bar, I2_bar, W0, W1, W2);
  bool uses_I2 = false;
  for (double d2 : W2) uses_I2 = uses_I2 || d2 != 0.0;

  // The volumetric part: per element (mean dilatation) or per point (standard).
  alignas(64) double U[8 * N], dU[8 * N];
  V energy = V{};
  if (mean_dilatation) {
    const V V0 = load<N>(&g.volume.lane[o]);
    for (int l = 0; l < N; ++l) {
      const VolumetricResponse response = material.volumetric(v[l] / V0[l]);
      energy[l] = V0[l] * response.energy;
      for (int q = 0; q < 8; ++q) {
        U[N * q + l] = 0.0;
        dU[N * q + l] = response.first;
      }
    }
  } else {
    for (int q = 0; q < 8; ++q) {
      for (int l = 0; l < N; ++l) {
        const VolumetricResponse response = material.volumetric(p[q].J[l]);
        U[N * q + l] = response.energy;
        dU[N * q + l] = response.first;
      }
    }
  }

  // Pass 2: w P_iJ = w [(s1 + s2 I1) F - s2 F C - (t - p) adj^T], t = (s1 I1 + 2 s2 I2) / (3 J),
  // and f_ai = sum over points and J of w P_iJ dN_a/dX_J.
  V f[24];
  for (V& fk : f) fk = V{};
  for (int q = 0; q < 8; ++q) {
    const PointKinematics<N>& k = p[q];
    const auto& G = g.gradient[q];
    const V w = load<N>(&g.weight[q].lane[o]);
    const V s1 = 2.0 * load<N>(W1 + N * q) * k.j23;
    const V s2 = 2.0 * load<N>(W2 + N * q) * k.j23 * k.j23;
    energy += w * (load<N>(W0 + N * q) + load<N>(U + N * q));
    const V wf = w * (s1 + s2 * k.I1);
    const V wt = w * ((s1 * k.I1 + 2.0 * s2 * k.I2) / (3.0 * k.J) - load<N>(dU + N * q));
    const V ws2 = w * s2;
    V wP[3][3];
    for (int i = 0; i < 3; ++i) {
      for (int K = 0; K < 3; ++K) {
        wP[i][K] = wf * k.F[i][K] - wt * k.adj[K][i];
        if (uses_I2) {
          wP[i][K] -= ws2 * (k.F[i][0] * k.C[0][K] + k.F[i][1] * k.C[1][K] + k.F[i][2] * k.C[2][K]);
        }
      }
    }
    for (int a = 0; a < 8; ++a) {
      const V g0 = load<N>(&G[a].lane[o]), g1 = load<N>(&G[8 + a].lane[o]),
              g2 = load<N>(&G[16 + a].lane[o]);
      for (int i = 0; i < 3; ++i) f[3 * a + i] += wP[i][0] * g0 + wP[i][1] * g1 + wP[i][2] * g2;
    }
  }

  for (int k = 0; k < 24; ++k) store<N>(&r.force[k].lane[o], f[k]);
  store<N>(&r.energy.lane[o], energy);
  store<N>(&r.min_J.lane[o], min_J);
  for (int l = 0; l < N; ++l) r.ok[o + l] = ok[l] != 0;
}

// The whole batch, N lanes at a time.
template <int N>
[[gnu::always_inline]] inline void lanes_force_all(const ElementBatchGeometry& g,
                                                   const BatchCoords& coords,
                                                   const UncoupledMaterial& material,
                                                   bool mean_dilatation, ElementBatchResponse& r) {
  static_assert(kBatchLanes % N == 0);
  for (int o = 0; o < kBatchLanes; o += N)
    lanes_force<N>(g, coords, material, mean_dilatation, o, r);
}

// One kernel per instruction set, with the vector width that fits its registers: 8 doubles per
// operation with AVX-512's 32 registers, 4 with AVX2 + FMA (its 16 registers would spill 8-wide
// values), 2 with the SSE2 of every x86-64. Only the kernels the CPU runs are called.
__attribute__((target("arch=x86-64-v4"))) void avx512_force(const ElementBatchGeometry& g,
                                                            const BatchCoords& coords,
                                                            const UncoupledMaterial& material,
                                                            bool mean_dilatation,
                                                            ElementBatchResponse& r) {
  lanes_force_all<8>(g, coords, material, mean_dilatation, r);
}
__attribute__((target("arch=x86-64-v3"))) void avx2_force(const ElementBatchGeometry& g,
                                                          const BatchCoords& coords,
                                                          const UncoupledMaterial& material,
                                                          bool mean_dilatation,
                                                          ElementBatchResponse& r) {
  lanes_force_all<4>(g, coords, material, mean_dilatation, r);
}
void sse2_force(const ElementBatchGeometry& g, const BatchCoords& coords,
                const UncoupledMaterial& material, bool mean_dilatation, ElementBatchResponse& r) {
  lanes_force_all<2>(g, coords, material, mean_dilatation, r);
}

}  // namespace

SimdLevel best_simd_level() {
  static const SimdLevel best = [] {
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v4")) return SimdLevel::avx512;
    if (__builtin_cpu_supports("x86-64-v3")) return SimdLevel::avx2;
    return SimdLevel::sse2;
  }();
  return best;
}

void evaluate_batch_force(const ElementBatchGeometry& geometry, const BatchCoords& x,
                          const UncoupledMaterial& material, Formulation formulation,
                          ElementBatchResponse& response, SimdLevel level) {
  if (level > best_simd_level())
    throw std::invalid_argument("element batch: this CPU does not run the requested kernel");
  const bool mean_dilatation = formulation == Formulation::mean_dilatation;
  switch (level) {
    case SimdLevel::avx512:
      return avx512_force(geometry, x, material, mean_dilatation, response);
    case SimdLevel::avx2:
      return avx2_force(geometry, x, material, mean_dilatation, response);
    case SimdLevel::sse2:
      return sse2_force(geometry, x, material, mean_dilatation, response);
  }
}

}  // namespace tongue::fem
