#pragma once
// One particle's cubic B-spline stencil (kernels/bspline.hpp) factored into rows along x, the form
// in which the transfers sweep a NodeTile (grid/node_tile.hpp), and the per-particle kernels on
// those rows.
//
// The weight of node base + (i, j[, k]) is w_ip = wx_i * W_r, r = j [+ 4 k], with the row weight
// W_r = wy_j [wz_k]; its gradient is (dwx_i W_r, wx_i dW_r/dy[, wx_i dW_r/dz]); and x_i - x_p =
// (ox_i, oy_j[, oz_k]). A sum over the stencil of a node value F times any of these is a sum over
// rows of a row factor times a 4-term sum along x. The kernels below therefore keep, per x place
// i, sums over the rows (4-wide, elementwise: vectorized), and contract with the x factors once
// at the end: about a third of the arithmetic of a node-by-node loop in 3D, and no per-node
// index.
#include <array>
#include <cstring>
#include <utility>

#include "solvers/mpm2grid/grid/node_tile.hpp"
#include "solvers/mpm2grid/kernels/bspline.hpp"

namespace suite::mpm2grid {

template <int Dim>
struct StencilRows {
  static constexpr int kRows = Dim == 2 ? 4 : 16;
  static constexpr int kCross = Dim - 1;  // axes across the rows (y[, z])

  Index<Dim> base{};          // first node of the stencil
  alignas(32) double wx[4];   // weights along x
  alignas(32) double dwx[4];  // their d/dx, 1/m
  alignas(32) double wxo[4];  // wx_i (x_i - x_p), m
  double w[kRows];            // row weights W_r
  double dw[kCross][kRows];   // dW_r/dy[, dW_r/dz], 1/m
  double wo[kCross][kRows];   // W_r (y_j - y_p)[, W_r (z_k - z_p)], m

  StencilRows(const Vec<Dim>& x, double h) {
    // in_cells() as in stencil_base(): the first node is the one touch_blocks() activated for.
    const double inv_h = 1 / h;
    double a[Dim][4], da[Dim][4], o[Dim][4];
    for (int d = 0; d < Dim; ++d) {
      base[d] = cubic_bspline_axis(in_cells(x[d], h), a[d], da[d]);
      for (int k = 0; k < 4; ++k) {
        da[d][k] *= inv_h;
        o[d][k] = (base[d] + k) * h - x[d];
      }
    }
    for (int i = 0; i < 4; ++i) wx[i] = a[0][i], dwx[i] = da[0][i], wxo[i] = a[0][i] * o[0][i];
    for (int r = 0; r < kRows; ++r) {
      const int j = r & 3;
      if constexpr (Dim == 2) {
        w[r] = a[1][j];
        dw[0][r] = da[1][j];
        wo[0][r] = a[1][j] * o[1][j];
      } else {
        const int k = r >> 2;
        w[r] = a[1][j] * a[2][k];
        dw[0][r] = da[1][j] * a[2][k];
        dw[1][r] = a[1][j] * da[2][k];
        wo[0][r] = w[r] * o[1][j];
        wo[1][r] = w[r] * o[2][k];
      }
    }
  }
};

namespace rows {

// Four doubles as one value of GCC's vector extension: one AVX register, or two SSE2 registers on
// the baseline (kernels/vector_clones.hpp). Copied in and out with memcpy (rows start at any
// double), and never passed by value (that would tie the functions to one calling convention).
// The operations are elementwise, in the order written: the same rounding as scalar code.
using Four = double __attribute__((vector_size(4 * sizeof(double))));

// row[i] += a x[i] (+ b y[i]), i = 0..3.
inline void axpy4(double* row, double a, const double* x) {
  Four r, u;
  std::memcpy(&r, row, sizeof r);
  std::memcpy(&u, x, sizeof u);
  r += a * u;
  std::memcpy(row, &r, sizeof r);
}
inline void axpy4(double* row, double a, const double* x, double b, const double* y) {
  Four r, u, w;
  std::memcpy(&r, row, sizeof r);
  std::memcpy(&u, x, sizeof u);
  std::memcpy(&w, y, sizeof w);
  r += a * u + b * w;
  std::memcpy(row, &r, sizeof r);
}

// row[i] += a x[i] + b y[i] + c z[i], i = 0..3.
inline void axpy4(double* row, double a, const double* x, double b, const double* y, double c, const double* z) {
  Four r, u, w, t;
  std::memcpy(&r, row, sizeof r);
  std::memcpy(&u, x, sizeof u);
  std::memcpy(&w, y, sizeof w);
  std::memcpy(&t, z, sizeof t);
  r += a * u + b * w + c * t;
  std::memcpy(row, &r, sizeof r);
}

// sums[k] = (m_k[0] + m_k[1]) + (m_k[2] + m_k[3]), k = 0 .. 3: four dot products at once from
// their elementwise products m_k, with vector shuffles instead of scalar adds.
inline void horizontal_sums(const Four* m, double* sums) {
  using Mask = long long __attribute__((vector_size(4 * sizeof(long long))));
  // [m0_0 + m0_1, m1_0 + m1_1, m0_2 + m0_3, m1_2 + m1_3], and the same for m2, m3
  const Four a = __builtin_shuffle(m[0], m[1], Mask{0, 4, 2, 6}) + __builtin_shuffle(m[0], m[1], Mask{1, 5, 3, 7});
  const Four b = __builtin_shuffle(m[2], m[3], Mask{0, 4, 2, 6}) + __builtin_shuffle(m[2], m[3], Mask{1, 5, 3, 7});
  const Four t = __builtin_shuffle(a, b, Mask{0, 1, 4, 5}) + __builtin_shuffle(a, b, Mask{2, 3, 6, 7});
  std::memcpy(sums, &t, sizeof t);
}

}  // namespace rows

// A node field sampled at a particle: sum_i w_ip F_i, its first moment sum_i w_ip F_i (x_i -
// x_p) and its gradient sum_i F_i grad w_ip (each only when asked for).
template <int Dim>
struct FieldSample {
  double value = 0;
  Vec<Dim> moment = Vec<Dim>::Zero();
  Vec<Dim> gradient = Vec<Dim>::Zero();
};

// Which components of a gradient sample_field computes: one bit per axis.
struct Axes {
  unsigned bits = 0;
  constexpr bool has(int axis) const { return (bits >> axis) & 1u; }
};
inline constexpr Axes kNoAxes{0u}, kAllAxes{~0u};
constexpr Axes only_axis(int axis) {
  return Axes{1u << axis};
}

// Calls f.template operator()<a>() for the axes a = 0 .. Dim - 1 in order, each a constant.
template <int Dim, class F>
void for_each_axis(F&& f) {
  [&]<int... a>(std::integer_sequence<int, a...>) {
    (f.template operator()<a>(), ...);
  }
  (std::make_integer_sequence<int, Dim>{});
}

namespace rows {

// A field sample from its sums over the rows (sample_fields): the contraction with the x
// factors, its products in the order of the outputs (value, moment, gradient) summed four at a
// time.
template <bool Moment, Axes Gradient, int Dim>
FieldSample<Dim> contract(const StencilRows<Dim>& s, const Four& P, const Four* Q, const Four* D) {
  constexpr int kCross = StencilRows<Dim>::kCross;
  Four wx, wxo, dwx;
  std::memcpy(&wx, s.wx, sizeof wx);
  std::memcpy(&wxo, s.wxo, sizeof wxo);
  std::memcpy(&dwx, s.dwx, sizeof dwx);
  constexpr int kMost = 1 + 2 * Dim;
  Four products[(kMost + 3) / 4 * 4]{};
  int n = 0;
  products[n++] = wx * P;
  if constexpr (Moment) {
    products[n++] = wxo * P;
    for (int e = 0; e < kCross; ++e) products[n++] = wx * Q[e];
  }
  if constexpr (Gradient.has(0)) products[n++] = dwx * P;
  for (int e = 0; e < kCross; ++e)
    if (Gradient.has(1 + e)) products[n++] = wx * D[e];
  alignas(32) double sums[(kMost + 3) / 4 * 4];
  for (int k = 0; k < n; k += 4) horizontal_sums(products + k, sums + k);
  FieldSample<Dim> out;
  n = 0;
  out.value = sums[n++];
  if constexpr (Moment)
    for (int d = 0; d < Dim; ++d) out.moment[d] = sums[n++];
  for (int d = 0; d < Dim; ++d)
    if (Gradient.has(d)) out.gradient[d] = sums[n++];
  return out;
}

}  // namespace rows

// Samples the tile fields f0, f0 + 1, ... (one per Gradient given) at a particle whose stencil
// starts at tile index `first`: each one's value, with Moment its moment, and its gradient
// components along its Gradient axes (the others are left 0; a divergence needs one per velocity
// component). The sums over the rows are vector values in a fully unrolled loop, so that the
// compiler keeps them in registers (as arrays updated through memory they made a chain of stores
// and reloads per row: 1.2x on the 3D step). The fields go through the rows together, sharing
// each row's weights (measured as fast as one field after the other, not faster). The same
// operations in the same order per field as axpy4's.
template <bool Moment, Axes... Gradient, int Dim, int Fields>
std::array<FieldSample<Dim>, sizeof...(Gradient)> sample_fields(const NodeTile<Dim, Fields>& tile, int f0,
                                                                const StencilRows<Dim>& s, int first) {
  using Tile = NodeTile<Dim, Fields>;
  using rows::Four;
  constexpr int kCross = StencilRows<Dim>::kCross;
  constexpr int kN = sizeof...(Gradient);
  constexpr std::array<Axes, kN> kGradient{Gradient...};
  Four P[kN]{};          // sum_r W_r F_ri
  Four Q[kN][kCross]{};  // sum_r W_r o_r F_ri (moments across)
  Four D[kN][kCross]{};  // sum_r dW_r F_ri (gradient across)
  const double* F = tile.field(f0) + first;
#pragma GCC unroll 16
  for (int r = 0; r < StencilRows<Dim>::kRows; ++r) {
#pragma GCC unroll 4
    for (int k = 0; k < kN; ++k) {
      Four row;
      std::memcpy(&row, F + k * Tile::kSize + Tile::row_offset(r), sizeof row);
      P[k] += s.w[r] * row;
      for (int e = 0; e < kCross; ++e) {
        if constexpr (Moment) Q[k][e] += s.wo[e][r] * row;
        if (kGradient[k].has(1 + e)) D[k][e] += s.dw[e][r] * row;  // constant: folded
      }
    }
  }
  std::array<FieldSample<Dim>, kN> out;
  [&]<int... k>(std::integer_sequence<int, k...>) {
    ((out[k] = rows::contract<Moment, kGradient[k]>(s, P[k], Q[k], D[k])), ...);
  }
  (std::make_integer_sequence<int, kN>{});
  return out;
}

// One field: sample_fields for field f.
template <bool Moment, Axes Gradient, int Dim, int Fields>
FieldSample<Dim> sample_field(const NodeTile<Dim, Fields>& tile, int f, const StencilRows<Dim>& s, int first) {
  return sample_fields<Moment, Gradient>(tile, f, s, first)[0];
}

// How a particle's stress enters P2G: none, isotropic (S = s I, the water's -V0 J p I: one term
// per axis instead of Dim) or a full matrix (the soil's V0 tau).
enum class StressForm { none, isotropic, full };

// APIC's P2G for one particle (transfer/apic.hpp) into tile fields 0 (mass) and 1 .. Dim
// (momentum), with the force on each node
//   f_i = -S grad w_ip + w_ip g     (S = V0 tau: S(0, 0) I when isotropic; g a body force, N)
// either into fields Dim + 1 .. 2 Dim (Fold false) or, times dt, into the momentum fields (Fold
// true: the node then holds m v + dt f, which is all the lumped and consistent drag solves read;
// one 3-term row update per axis instead of two 2-term ones, and Dim fewer fields):
//   m w_ip,   m w_ip (v + C (x_i - x_p)) [+ dt f_i],   [f_i],
// and, with extra_field >= 0, e w_ip into that field (the drag coefficients or pressures).
// Each row's update is a few x vectors times per-row coefficients; the coefficients (W_r times
// the particle's values) are computed for four rows at a time as vector values, in the same
// operations and order as one row at a time: 4x fewer instructions for them, 1.08x on the 3D
// step.
template <StressForm Form, bool Fold, int Dim, int Fields>
void scatter_apic(NodeTile<Dim, Fields>& tile, const StencilRows<Dim>& s, int first, double m, const Vec<Dim>& v,
                  const Mat<Dim>& C, const Mat<Dim>& S, const Vec<Dim>& g, double dt, int extra_field = -1,
                  double e = 0) {
  static_assert(Fields >= (Fold ? 1 + Dim : 1 + 2 * Dim), "the APIC tile holds mass, momentum and force");
  using Tile = NodeTile<Dim, Fields>;
  using rows::Four;
  constexpr int kRows = StencilRows<Dim>::kRows;
  constexpr int kCross = StencilRows<Dim>::kCross;
  const Vec<Dim> mv = m * v;
  const Mat<Dim> mC = m * C;
  const bool forced = Form != StressForm::none || !g.isZero(0.0);
  // Per-row coefficients: mass m W_r; momentum along wx (alpha [+ dt delta]), along wxo (beta)
  // [and along dwx, dt gamma]; force along dwx (gamma) and wx (delta); extra e W_r. With
  //   alpha = W_r m v_a + sum_e m C_a,e+1 o_e,r,  beta = W_r m C_a0,
  //   gamma = -S_a0 W_r,  delta = W_r g_a - sum_e S_a,e+1 dW_r,e.
  alignas(32) double mass[kRows], along_wx[Dim][kRows], along_wxo[Dim][kRows], along_dwx[Dim][kRows],
      force_wx[Dim][kRows], extra[kRows];
  const auto store = [](double* at, const Four& f) { std::memcpy(at, &f, sizeof f); };
  for (int q = 0; q < kRows; q += 4) {
    Four W, wo[kCross], dw[kCross];
    std::memcpy(&W, s.w + q, sizeof W);
    for (int c = 0; c < kCross; ++c) {
      std::memcpy(&wo[c], s.wo[c] + q, sizeof W);
      std::memcpy(&dw[c], s.dw[c] + q, sizeof W);
    }
    store(mass + q, m * W);
    if (extra_field >= 0) store(extra + q, e * W);
    for (int a = 0; a < Dim; ++a) {
      Four alpha = W * mv[a];
      for (int c = 0; c < kCross; ++c) alpha += mC(a, 1 + c) * wo[c];
      const Four beta = W * mC(a, 0);
      Four gamma{}, delta = W * g[a];
      if constexpr (Form == StressForm::full) {
        gamma = -S(a, 0) * W;
        for (int c = 0; c < kCross; ++c) delta -= S(a, 1 + c) * dw[c];
      } else if constexpr (Form == StressForm::isotropic) {
        if (a == 0)
          gamma = -S(0, 0) * W;
        else
          delta -= S(0, 0) * dw[a - 1];
      }
      store(along_wxo[a] + q, beta);
      if constexpr (Fold) {
        store(along_wx[a] + q, alpha + dt * delta);
        store(along_dwx[a] + q, dt * gamma);
      } else {
        store(along_wx[a] + q, alpha);
        store(along_dwx[a] + q, gamma);
        store(force_wx[a] + q, delta);
      }
    }
  }
  for (int r = 0; r < kRows; ++r) {
    const int at = first + Tile::row_offset(r);
    rows::axpy4(tile.field(0) + at, mass[r], s.wx);
    for (int a = 0; a < Dim; ++a) {
      double* momentum = tile.field(1 + a) + at;
      if constexpr (Fold) {
        if (Form == StressForm::full || (Form == StressForm::isotropic && a == 0))
          rows::axpy4(momentum, along_wx[a][r], s.wx, along_wxo[a][r], s.wxo, along_dwx[a][r], s.dwx);
        else
          rows::axpy4(momentum, along_wx[a][r], s.wx, along_wxo[a][r], s.wxo);
      } else {
        rows::axpy4(momentum, along_wx[a][r], s.wx, along_wxo[a][r], s.wxo);
        if (forced) rows::axpy4(tile.field(1 + Dim + a) + at, along_dwx[a][r], s.dwx, force_wx[a][r], s.wx);
      }
    }
    if (extra_field >= 0) rows::axpy4(tile.field(extra_field) + at, extra[r], s.wx);
  }
}

// Calls body(p, rows, first) for the particles at x in order, with `tile` covering each one's
// group: where the group changes, leave() is called for the old group (if any) and enter() after
// the tile covers the new one; leave() once more at the end. Particles in group order (transfer/
// particle_order.hpp) make one enter/leave per group.
template <int Dim, int Fields, class Enter, class Leave, class Body>
void sweep_groups(const std::vector<Vec<Dim>>& x, const BlockGrid<Dim>& grid, NodeTile<Dim, Fields>& tile,
                  Enter&& enter, Leave&& leave, Body&& body) {
  using Tile = NodeTile<Dim, Fields>;
  const double h = grid.spacing();
  tile.release();
  for (std::size_t p = 0; p < x.size(); ++p) {
    const StencilRows<Dim> s(x[p], h);
    const Index<Dim> g = Tile::group_of(s.base);
    if (!tile.covers(g)) {
      if (tile.covering()) leave();
      tile.cover(grid, g);
      enter();
    }
    body(p, s, Tile::first_index(s.base, g));
  }
  if (tile.covering()) leave();
}

}  // namespace suite::mpm2grid
