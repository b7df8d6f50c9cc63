#pragma once
// Cubic B-spline interpolation weights (docs/methods/mpm2grid.md, "Discretization"):
//   N(x) = 1/2 |x|^3 - |x|^2 + 2/3   on [0, 1),   1/6 (2 - |x|)^3   on [1, 2),   0 beyond,
// x in units of the grid spacing h, tensor product over the dimensions. A particle at x_p
// touches the 4^Dim nodes base + k, k in {0..3}^Dim, base = floor(x_p / h) - 1 (grid origin at 0).
// The weights are a partition of unity and reproduce linear functions (sum_i w_ip x_i = x_p),
// which is what makes APIC's transfers conserve angular momentum.
#include <Eigen/Core>
#include <array>
#include <cmath>

namespace suite::mpm2grid {

template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;
template <int Dim>
using Mat = Eigen::Matrix<double, Dim, Dim>;
template <int Dim>
using Index = std::array<int, Dim>;

// N(r) and dN/dr for one axis.
inline double cubic_bspline(double r) {
  const double a = std::abs(r);
  if (a < 1) return 0.5 * a * a * a - a * a + 2.0 / 3.0;
  if (a < 2) return (2 - a) * (2 - a) * (2 - a) / 6.0;
  return 0;
}

inline double cubic_bspline_derivative(double r) {
  const double a = std::abs(r), s = r < 0 ? -1.0 : 1.0;
  if (a < 1) return s * (1.5 * a * a - 2 * a);
  if (a < 2) return -s * 0.5 * (2 - a) * (2 - a);
  return 0;
}

// The integral of N from -infinity to r: 0 below -2, 1/2 at 0, 1 above 2. A node at distance
// r h inside a wall has the fraction cubic_bspline_integral(r) of its weight's support inside.
inline double cubic_bspline_integral(double r) {
  const double a = std::abs(r);
  double half;  // the integral of N from 0 to |r|
  if (a < 1)
    half = a * a * a * a / 8 - a * a * a / 3 + 2 * a / 3;
  else if (a < 2)
    half = 11.0 / 24 + (1 - (2 - a) * (2 - a) * (2 - a) * (2 - a)) / 24;
  else
    half = 0.5;
  return r < 0 ? 0.5 - half : 0.5 + half;
}

// The four weights N(r_k) and derivatives dN/dr(r_k) along one axis for a particle at xi (in
// units of h) and the nodes base + k, base = floor(xi) - 1, k = 0..3, in closed form: with the
// fraction f = xi - floor(xi) and g = 1 - f the distances are r_k = 1 + f, f, -g, -(1 + g), so
//   N = g^3/6,  f^3/2 - f^2 + 2/3,  g^3/2 - g^2 + 2/3,  f^3/6
//   dN/dr = -g^2/2,  3f^2/2 - 2f,  2g - 3g^2/2,  f^2/2
// (the polynomials above without their branches). Returns base.
inline int cubic_bspline_axis(double xi, double* w, double* dw) {
  const double floor_xi = std::floor(xi), f = xi - floor_xi, g = 1 - f;
  const double f2 = f * f, g2 = g * g;
  w[0] = g2 * g * (1.0 / 6);
  w[1] = 0.5 * f2 * f - f2 + 2.0 / 3;
  w[2] = 0.5 * g2 * g - g2 + 2.0 / 3;
  w[3] = f2 * f * (1.0 / 6);
  dw[0] = -0.5 * g2;
  dw[1] = 1.5 * f2 - 2 * f;
  dw[2] = 2 * g - 1.5 * g2;
  dw[3] = 0.5 * f2;
  return static_cast<int>(floor_xi) - 1;
}

// A coordinate in units of the grid spacing, x * (1 / h). Every stencil, transfer and home block
// computes it this one way, so that they agree on the node below a particle; a multiplication,
// as it runs for every particle in every transfer.
inline double in_cells(double x, double h) {
  return x * (1 / h);
}

// The first node of the stencil of a particle at x (base = floor(x / h) - 1 per axis), as
// Stencil and every transfer compute it.
template <int Dim>
Index<Dim> stencil_base(const Eigen::Matrix<double, Dim, 1>& x, double h) {
  Index<Dim> base;
  for (int d = 0; d < Dim; ++d) base[d] = static_cast<int>(std::floor(in_cells(x[d], h))) - 1;
  return base;
}

// APIC's inertia-like tensor for cubic B-splines is D = h^2 / 3 I, so D^-1 = 3 / h^2.
inline double apic_inverse_d(double h) {
  return 3.0 / (h * h);
}

// The 4^Dim weights of one particle and their gradients (per metre).
template <int Dim>
struct Stencil {
  Index<Dim> base{};                            // node index of corner k = 0
  std::array<std::array<double, 4>, Dim> w{};   // per axis
  std::array<std::array<double, 4>, Dim> dw{};  // per axis, d/dx in 1/m

  Stencil() = default;
  // x in metres relative to the grid origin, h the node spacing.
  Stencil(const Vec<Dim>& x, double h) {
    for (int d = 0; d < Dim; ++d) {
      base[d] = cubic_bspline_axis(in_cells(x[d], h), w[d].data(), dw[d].data());
      for (int k = 0; k < 4; ++k) dw[d][k] /= h;
    }
  }

  static constexpr int kNodes = Dim == 2 ? 16 : 64;

  // Node n's corner index along axis d (n in for_each order, x fastest).
  static constexpr int corner_index(int n, int d) { return (n >> (2 * d)) & 3; }

  // Every node's weight, in for_each order: the same values as weight(), computed in the same
  // order, for loops over the nodes.
  void weights(std::array<double, kNodes>& out) const {
    for (int n = 0; n < kNodes; ++n) {
      double v = w[0][corner_index(n, 0)];
      for (int d = 1; d < Dim; ++d) v *= w[d][corner_index(n, d)];
      out[n] = v;
    }
  }
  double weight(const Index<Dim>& k) const {
    double v = 1;
    for (int d = 0; d < Dim; ++d) v *= w[d][k[d]];
    return v;
  }

  Vec<Dim> gradient(const Index<Dim>& k) const {
    Vec<Dim> g;
    for (int d = 0; d < Dim; ++d) {
      double v = dw[d][k[d]];
      for (int e = 0; e < Dim; ++e)
        if (e != d) v *= w[e][k[e]];
      g[d] = v;
    }
    return g;
  }

  // Calls f(k, node index) for every corner k of the 4^Dim stencil, x fastest.
  template <class F>
  void for_each(F&& f) const {
    Index<Dim> k{};
    for (int n = 0; n < kNodes; ++n) {
      int r = n;
      Index<Dim> node;
      for (int d = 0; d < Dim; ++d) {
        k[d] = r % 4;
        r /= 4;
        node[d] = base[d] + k[d];
      }
      f(k, node);
    }
  }
};

}  // namespace suite::mpm2grid
