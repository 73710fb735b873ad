#pragma once
// Internal to the batch kernels (hex8_batch.cpp, hex8_batch_tangent.cpp): GCC vector types of 2,
// 4 or 8 doubles and the kinematics of one Gauss point of N elements on them. Everything here has
// internal linkage and is always inlined into a kernel compiled for one instruction set, so each
// kernel gets its own copy and the linker never picks an AVX-512 copy for baseline code.
#include <cmath>
#include <cstring>

#include "fem/element/hex8_batch.hpp"

// The argument-passing ABI of these vector types differs between SSE2 and AVX-512 code (what
// -Wpsabi warns about); it never matters since no helper here is ever called out of line.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace tongue::fem {
namespace {  // NOLINT(google-build-namespaces): internal linkage on purpose, see above

// N doubles in one vector of GCC's vector extensions: 8 for AVX-512, 4 for AVX2, 2 for SSE2.
template <int N>
struct VectorOf {
  using type [[gnu::vector_size(N * sizeof(double))]] = double;
};
template <int N>
using Lanes = typename VectorOf<N>::type;

template <int N>
[[gnu::always_inline]] inline Lanes<N> load(const double* p) {
  Lanes<N> r;
  std::memcpy(&r, p, sizeof r);
  return r;
}
template <int N>
[[gnu::always_inline]] inline void store(double* p, Lanes<N> x) {
  std::memcpy(p, &x, sizeof x);
}

// J^{-1/3} lane by lane. When every lane lies in [0.5, 2] (nearly incompressible tissue is
// within a few % of J = 1): a degree-4 polynomial start, interpolating J^{-1/3} at the Chebyshev
// nodes of that interval (relative error e <= 1.5e-3), then three Newton steps for y^{-3} = J,
// y <- y + y (1 - J y^3) / 3, each taking e to about 2 e^2: 4.5e-6, 4e-11, then round-off.
// Otherwise std::cbrt lane by lane.
template <int N>
[[gnu::always_inline]] inline Lanes<N> inverse_cube_root(Lanes<N> J) {
  const auto inside = (J >= 0.5) & (J <= 2.0);  // -1 where true, 0 where false
  bool all_inside = true;
  for (int l = 0; l < N; ++l) all_inside = all_inside && inside[l] != 0;
  if (!all_inside) {
    Lanes<N> y;
    for (int l = 0; l < N; ++l) y[l] = 1.0 / std::cbrt(J[l]);
    return y;
  }
  Lanes<N> y = 1.863911204977621 +
               J * (-1.7615233559419634 +
                    J * (1.3433317115723395 + J * (-0.5285183834495579 + J * 0.08176329728635946)));
  for (int step = 0; step < 3; ++step) y += y * (1.0 - J * (y * y * y)) * (1.0 / 3.0);
  return y;
}

// Per Gauss point, what the stress and the tangent need after the material's derivatives are
// known.
template <int N>
struct PointKinematics {
  Lanes<N> F[3][3], adj[3][3], C[3][3];  // F, adj F = J F^{-1}, C = F^T F
  Lanes<N> J, I1, I2, j23;               // det F, invariants of C, J^{-2/3}
};

// The kinematics at Gauss point q of lanes o .. o + N - 1, from their nodal positions x
// (x[3 a + i], as BatchCoords).
template <int N>
[[gnu::always_inline]] inline void point_kinematics(const ElementBatchGeometry& g,
                                                    const Lanes<N> (&x)[24], int q, int o,
                                                    PointKinematics<N>& k) {
  using V = Lanes<N>;
  const auto& G = g.gradient[q];
  auto& F = k.F;
  for (int i = 0; i < 3; ++i) {
    for (int J = 0; J < 3; ++J) {
      V sum = x[i] * load<N>(&G[8 * J].lane[o]);
      for (int a = 1; a < 8; ++a) sum += x[3 * a + i] * load<N>(&G[8 * J + a].lane[o]);
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

  auto& C = k.C;
  for (int I = 0; I < 3; ++I) {
    for (int K = I; K < 3; ++K) {
      C[I][K] = F[0][I] * F[0][K] + F[1][I] * F[1][K] + F[2][I] * F[2][K];
      C[K][I] = C[I][K];
    }
  }
  k.I1 = C[0][0] + C[1][1] + C[2][2];
  const V CC = C[0][0] * C[0][0] + C[1][1] * C[1][1] + C[2][2] * C[2][2] +
               2.0 * (C[0][1] * C[0][1] + C[0][2] * C[0][2] + C[1][2] * C[1][2]);
  k.I2 = 0.5 * (k.I1 * k.I1 - CC);
  const V y = inverse_cube_root<N>(k.J);
  k.j23 = y * y;
}

}  // namespace
}  // namespace tongue::fem
