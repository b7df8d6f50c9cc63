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
#include <span>
#include <utility>

#include "solvers/mpm2grid/grid/node_tile.hpp"
#include "solvers/mpm2grid/kernels/bspline.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"

namespace suite::mpm2grid {

namespace rows {
// Four doubles as one value of GCC's vector extension: one AVX register, or two SSE2 registers on
// the baseline (kernels/vector_clones.hpp). Copied in and out with memcpy (rows start at any
// double), and never passed by value (that would tie the functions to one calling convention).
// The operations are elementwise, in the order written: the same rounding as scalar code.
using Four = double __attribute__((vector_size(4 * sizeof(double))));
}  // namespace rows

template <int Dim>
struct StencilRows {
  static constexpr int kRows = Dim == 2 ? 4 : 16;
  static constexpr int kCross = Dim - 1;  // axes across the rows (y[, z])

  Index<Dim> base{};          // first node of the stencil
  alignas(32) double wx[4];   // weights along x
  alignas(32) double dwx[4];  // their d/dx, 1/m
  alignas(32) double wxo[4];  // wx_i (x_i - x_p), m
  alignas(32) double w[kRows];           // row weights W_r
  alignas(32) double dw[kCross][kRows];  // dW_r/dy[, dW_r/dz], 1/m
  alignas(32) double wo[kCross][kRows];  // W_r (y_j - y_p)[, W_r (z_k - z_p)], m
  // The row factors per axis across, e = 0 for y[, 1 for z]: W_r = wa[0][j] [wa[1][k]].
  alignas(32) double wa[kCross][4];   // weights
  alignas(32) double dwa[kCross][4];  // their derivatives, 1/m
  alignas(32) double wao[kCross][4];  // weights times offsets, m

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
    for (int e = 0; e < kCross; ++e)
      for (int i = 0; i < 4; ++i)
        wa[e][i] = a[1 + e][i], dwa[e][i] = da[1 + e][i], wao[e][i] = a[1 + e][i] * o[1 + e][i];
    if constexpr (Dim == 2) {
      for (int j = 0; j < 4; ++j) w[j] = a[1][j], dw[0][j] = da[1][j], wo[0][j] = a[1][j] * o[1][j];
    } else {
      // The four rows j = 0 .. 3 at one z place k as vector values (the same products as row by
      // row): 20 vector products instead of 80 scalar ones, a saving in every transfer.
      rows::Four ay, day, oy;
      std::memcpy(&ay, a[1], sizeof ay);
      std::memcpy(&day, da[1], sizeof day);
      std::memcpy(&oy, o[1], sizeof oy);
      const auto store = [](double* at, const rows::Four& f) { std::memcpy(at, &f, sizeof f); };
      for (int k = 0; k < 4; ++k) {
        const rows::Four W = ay * a[2][k];
        store(w + 4 * k, W);
        store(dw[0] + 4 * k, day * a[2][k]);
        store(dw[1] + 4 * k, ay * da[2][k]);
        store(wo[0] + 4 * k, W * oy);
        store(wo[1] + 4 * k, W * o[2][k]);
      }
    }
  }
};

namespace rows {

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
// component). The sums over the rows are vector values in fully unrolled loops, so that the
// compiler keeps them in registers (as arrays updated through memory they made a chain of stores
// and reloads per row, which slowed the step). In 3D the sums are factored by axis, one field
// after the other (8 sums in registers, faster than 5 per row with all fields together, whose 15
// sums spilled); in 2D the fields go through the rows together, sharing each row's weights.
// (The measurements: docs/mpm2grid.md, "Benchmarks".)
template <bool Moment, Axes... Gradient, int Dim, int Fields>
std::array<FieldSample<Dim>, sizeof...(Gradient)> sample_fields(const NodeTile<Dim, Fields>& tile, int f0,
                                                                const StencilRows<Dim>& s, int first) {
  using Tile = NodeTile<Dim, Fields>;
  using rows::Four;
  constexpr int kCross = StencilRows<Dim>::kCross;
  constexpr int kN = sizeof...(Gradient);
  constexpr std::array<Axes, kN> kGradient{Gradient...};
  const double* F = tile.field(f0) + first;
  std::array<FieldSample<Dim>, kN> out;
  if constexpr (Dim == 3) {
    // Factored by axis: per z place c, sums over the four rows j with the y factors (A, B, G),
    // then those summed with the z factors. 3 products per row and field and 5 per z place
    // instead of 5 per row (a sample with moment and full gradient: 68 vector products, not 80),
    // with 8 sums in registers per field, one field after the other.
    [&]<int... k>(std::integer_sequence<int, k...>) {
      ((out[k] =
            [&] {
              constexpr Axes G = kGradient[k];
              Four P{}, Q[2]{}, D[2]{};
#pragma GCC unroll 4
              for (int c = 0; c < 4; ++c) {
                Four A{}, B{}, Gy{};
#pragma GCC unroll 4
                for (int j = 0; j < 4; ++j) {
                  Four row;
                  std::memcpy(&row, F + k * Tile::kSize + Tile::row_offset(j + 4 * c), sizeof row);
                  A += s.wa[0][j] * row;
                  if constexpr (Moment) B += s.wao[0][j] * row;
                  if constexpr (G.has(1)) Gy += s.dwa[0][j] * row;
                }
                P += s.wa[1][c] * A;
                if constexpr (Moment) {
                  Q[0] += s.wa[1][c] * B;
                  Q[1] += s.wao[1][c] * A;
                }
                if constexpr (G.has(1)) D[0] += s.wa[1][c] * Gy;
                if constexpr (G.has(2)) D[1] += s.dwa[1][c] * A;
              }
              return rows::contract<Moment, G>(s, P, Q, D);
            }()),
       ...);
    }
    (std::make_integer_sequence<int, kN>{});
  } else {
    Four P[kN]{};          // sum_r W_r F_ri
    Four Q[kN][kCross]{};  // sum_r W_r o_r F_ri (moments across)
    Four D[kN][kCross]{};  // sum_r dW_r F_ri (gradient across)
#pragma GCC unroll 4
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
    [&]<int... k>(std::integer_sequence<int, k...>) {
      ((out[k] = rows::contract<Moment, kGradient[k]>(s, P[k], Q[k], D[k])), ...);
    }
    (std::make_integer_sequence<int, kN>{});
  }
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
// true: the node then holds m v + dt f, which is all the lumped and consistent drag solves read,
// and Dim fewer fields):
//   m w_ip,   m w_ip (v + C (x_i - x_p)) [+ dt f_i],   [f_i],
// and, with extra_field >= 0, e w_ip into that field (the drag coefficients or pressures).
// Each row's update is W_r times a vector along x fixed for the particle (the mass m wx, the
// extra e wx, and the parts of the momentum and force along x: m C_a0 wxo, -S_a0 dwx) plus a
// per-row coefficient times wx (the rest, from the offsets and derivatives across): two products
// per row and momentum component. The per-row coefficients are computed for four rows at a time
// as vector values: 4x fewer instructions for them.
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
  // Whether S_a0 (the stress's part along x of component a) is there.
  constexpr auto along_x = [](int a) { return Form == StressForm::full || (Form == StressForm::isotropic && a == 0); };
  const auto load = [](Four& f, const double* at) { std::memcpy(&f, at, sizeof f); };
  const auto store = [](double* at, const Four& f) { std::memcpy(at, &f, sizeof f); };
  const auto add = [&](double* at, const Four& f) {
    Four r;
    load(r, at);
    r += f;
    store(at, r);
  };
  Four wx, wxo, dwx;
  load(wx, s.wx), load(wxo, s.wxo), load(dwx, s.dwx);
  // The vectors along x that W_r multiplies.
  const Four mass_x = m * wx, extra_x = e * wx;
  Four momentum_x[Dim], force_x[Dim];
  for (int a = 0; a < Dim; ++a) {
    momentum_x[a] = mC(a, 0) * wxo;
    force_x[a] = Four{};
    if (along_x(a)) {
      if constexpr (Fold)
        momentum_x[a] -= (dt * S(a, 0)) * dwx;
      else
        force_x[a] = -S(a, 0) * dwx;
    }
  }
  // The per-row coefficients of wx: momentum alpha [+ dt delta], force delta, with
  //   alpha = W_r m v_a + sum_e m C_a,e+1 o_e,r,  delta = W_r g_a - sum_e S_a,e+1 dW_r,e.
  alignas(32) double along_wx[Dim][kRows], force_wx[Dim][kRows];
  for (int q = 0; q < kRows; q += 4) {
    Four W, wo[kCross], dw[kCross];
    load(W, s.w + q);
    for (int c = 0; c < kCross; ++c) load(wo[c], s.wo[c] + q), load(dw[c], s.dw[c] + q);
    for (int a = 0; a < Dim; ++a) {
      Four alpha = W * mv[a];
      for (int c = 0; c < kCross; ++c) alpha += mC(a, 1 + c) * wo[c];
      Four delta = W * g[a];
      if constexpr (Form == StressForm::full) {
        for (int c = 0; c < kCross; ++c) delta -= S(a, 1 + c) * dw[c];
      } else if constexpr (Form == StressForm::isotropic) {
        if (a > 0) delta -= S(0, 0) * dw[a - 1];
      }
      if constexpr (Fold) {
        store(along_wx[a] + q, alpha + dt * delta);
      } else {
        store(along_wx[a] + q, alpha);
        store(force_wx[a] + q, delta);
      }
    }
  }
  for (int r = 0; r < kRows; ++r) {
    const int at = first + Tile::row_offset(r);
    const double W = s.w[r];
    add(tile.field(0) + at, W * mass_x);
    for (int a = 0; a < Dim; ++a) {
      add(tile.field(1 + a) + at, along_wx[a][r] * wx + W * momentum_x[a]);
      if constexpr (!Fold) {
        if (!forced) continue;
        if (along_x(a))
          add(tile.field(1 + Dim + a) + at, force_wx[a][r] * wx + W * force_x[a]);
        else
          add(tile.field(1 + Dim + a) + at, force_wx[a][r] * wx);
      }
    }
    if (extra_field >= 0) add(tile.field(extra_field) + at, W * extra_x);
  }
}

// Calls body(p, rows, first) for the particles at x in order (those of `subset` only), with
// `tile` covering each one's group: where the group changes, leave() is called for the old group
// (if any) and enter() after the tile covers the new one; leave() once more at the end. Particles
// in group order (transfer/particle_order.hpp) make one enter/leave per group; groups without a
// particle of the subset are not entered. With `runs`, only the particles of those runs, run after
// run (a thread's part of a sweep: transfer/sweep_schedule.hpp).
template <int Dim, int Fields, class Enter, class Leave, class Body>
void sweep_groups(const std::vector<Vec<Dim>>& x, const BlockGrid<Dim>& grid, NodeTile<Dim, Fields>& tile,
                  Enter&& enter, Leave&& leave, Body&& body, const ParticleSubset& subset = {},
                  std::span<const ParticleRun> runs = {}) {
  using Tile = NodeTile<Dim, Fields>;
  const double h = grid.spacing();
  tile.release();
  const auto sweep = [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      if (!subset.has(p)) continue;
      const StencilRows<Dim> s(x[p], h);
      const Index<Dim> g = Tile::group_of(s.base);
      if (!tile.covers(g)) {
        if (tile.covering()) leave();
        tile.cover(grid, g);
        enter();
      }
      body(p, s, Tile::first_index(s.base, g));
    }
  };
  if (runs.empty())
    sweep(0, x.size());
  else
    for (const ParticleRun& r : runs) sweep(r.begin, r.end);
  if (tile.covering()) leave();
}

}  // namespace suite::mpm2grid
