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

inline double dot4(const double* a, const double* b) {
  return (a[0] * b[0] + a[1] * b[1]) + (a[2] * b[2] + a[3] * b[3]);
}

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

}  // namespace rows

// A node field sampled at a particle: sum_i w_ip F_i, its first moment sum_i w_ip F_i (x_i -
// x_p) and its gradient sum_i F_i grad w_ip (each only when asked for).
template <int Dim>
struct FieldSample {
  double value = 0;
  Vec<Dim> moment = Vec<Dim>::Zero();
  Vec<Dim> gradient = Vec<Dim>::Zero();
};

// Samples tile field f at a particle whose stencil starts at tile index `first`. The sums over
// the rows are vector values in a fully unrolled loop, so that the compiler keeps them in
// registers (as arrays updated through memory they made a chain of stores and reloads per row:
// 1.2x on the 3D step); the same operations in the same order as axpy4's.
template <bool Moment, bool Gradient, int Dim, int Fields>
FieldSample<Dim> sample_field(const NodeTile<Dim, Fields>& tile, int f, const StencilRows<Dim>& s, int first) {
  using Tile = NodeTile<Dim, Fields>;
  using rows::Four;
  constexpr int kCross = StencilRows<Dim>::kCross;
  Four P{};          // sum_r W_r F_ri
  Four Q[kCross]{};  // sum_r W_r o_r F_ri (moments across)
  Four D[kCross]{};  // sum_r dW_r F_ri (gradient across)
  const double* F = tile.field(f) + first;
#pragma GCC unroll 16
  for (int r = 0; r < StencilRows<Dim>::kRows; ++r) {
    Four row;
    std::memcpy(&row, F + Tile::row_offset(r), sizeof row);
    P += s.w[r] * row;
    for (int e = 0; e < kCross; ++e) {
      if constexpr (Moment) Q[e] += s.wo[e][r] * row;
      if constexpr (Gradient) D[e] += s.dw[e][r] * row;
    }
  }
  const auto dot = [](const double* a, const Four& b) {
    alignas(32) double v[4];
    std::memcpy(v, &b, sizeof v);
    return rows::dot4(a, v);
  };
  FieldSample<Dim> out;
  out.value = dot(s.wx, P);
  if constexpr (Moment) {
    out.moment[0] = dot(s.wxo, P);
    for (int e = 0; e < kCross; ++e) out.moment[1 + e] = dot(s.wx, Q[e]);
  }
  if constexpr (Gradient) {
    out.gradient[0] = dot(s.dwx, P);
    for (int e = 0; e < kCross; ++e) out.gradient[1 + e] = dot(s.wx, D[e]);
  }
  return out;
}

// Adds c[q] w_ip to tile fields f0 + q, q = 0 .. n - 1, over the particle's stencil.
template <int Dim, int Fields>
void scatter_weighted(NodeTile<Dim, Fields>& tile, int f0, const double* c, int n, const StencilRows<Dim>& s,
                      int first) {
  using Tile = NodeTile<Dim, Fields>;
  for (int r = 0; r < StencilRows<Dim>::kRows; ++r)
    for (int q = 0; q < n; ++q) rows::axpy4(tile.field(f0 + q) + first + Tile::row_offset(r), c[q] * s.w[r], s.wx);
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
//   m w_ip,   m w_ip (v + C (x_i - x_p)) [+ dt f_i],   [f_i].
template <StressForm Form, bool Fold, int Dim, int Fields>
void scatter_apic(NodeTile<Dim, Fields>& tile, const StencilRows<Dim>& s, int first, double m, const Vec<Dim>& v,
                  const Mat<Dim>& C, const Mat<Dim>& S, const Vec<Dim>& g, double dt) {
  static_assert(Fields >= (Fold ? 1 + Dim : 1 + 2 * Dim), "the APIC tile holds mass, momentum and force");
  using Tile = NodeTile<Dim, Fields>;
  constexpr int kCross = StencilRows<Dim>::kCross;
  const Vec<Dim> mv = m * v;
  const Mat<Dim> mC = m * C;
  const bool forced = Form != StressForm::none || !g.isZero(0.0);
  for (int r = 0; r < StencilRows<Dim>::kRows; ++r) {
    const int at = first + Tile::row_offset(r);
    const double W = s.w[r];
    rows::axpy4(tile.field(0) + at, m * W, s.wx);
    for (int a = 0; a < Dim; ++a) {
      // momentum: m W_r (v_a + sum_e C_a,e+1 o_e) wx_i + m C_a0 W_r wx_i ox_i
      double alpha = W * mv[a];
      for (int e = 0; e < kCross; ++e) alpha += mC(a, 1 + e) * s.wo[e][r];
      const double beta = W * mC(a, 0);
      // force: gamma dwx_i + delta wx_i, gamma = -S_a0 W_r, delta = W_r g_a - sum_e S_a,e+1 dW_r,e
      double gamma = 0, delta = W * g[a];
      if constexpr (Form == StressForm::full) {
        gamma = -S(a, 0) * W;
        for (int e = 0; e < kCross; ++e) delta -= S(a, 1 + e) * s.dw[e][r];
      } else if constexpr (Form == StressForm::isotropic) {
        if (a == 0)
          gamma = -S(0, 0) * W;
        else
          delta -= S(0, 0) * s.dw[a - 1][r];
      }
      double* momentum = tile.field(1 + a) + at;
      if constexpr (Fold) {
        if (Form == StressForm::full || (Form == StressForm::isotropic && a == 0))
          rows::axpy4(momentum, alpha + dt * delta, s.wx, beta, s.wxo, dt * gamma, s.dwx);
        else
          rows::axpy4(momentum, alpha + dt * delta, s.wx, beta, s.wxo);
      } else {
        rows::axpy4(momentum, alpha, s.wx, beta, s.wxo);
        if (forced) rows::axpy4(tile.field(1 + Dim + a) + at, gamma, s.dwx, delta, s.wx);
      }
    }
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
