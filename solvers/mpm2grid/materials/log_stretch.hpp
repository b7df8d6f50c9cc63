#pragma once
// The Hencky strain of a deformation gradient from the eigenvalues of b = F F^T alone, without
// its eigenvectors: what an elastic soil particle needs (its Kirchhoff stress is a function of
// log V, V = sqrt(b) the left stretch). In 3D cheaper than the eigen-solver of left_stretch()
// (polar_svd.hpp; docs/mpm2grid.md, "Benchmarks"), which plastic returns still use for their
// principal directions; in 2D it saves left_stretch()'s half-angle square roots.
//
// Eigenvalues, descending. 2D: (b00 + b11)/2 + |((b00 - b11)/2, b01)|. 3D: the trigonometric
// closed form on the deviator of b (Smith 1961): m = tr(b)/3, p = sqrt(tr((b - m I)^2) / 6),
// cos(3 phi) = det(b - m I) / (2 p^3), lambda_1 = m + 2 p cos(phi), lambda_3 = m + 2 p cos(phi +
// 2 pi / 3) = m - p (cos(phi) + sqrt(3) sin(phi)) (one sincos), lambda_2 = 3 m - lambda_1 -
// lambda_3. Where two eigenvalues meet, phi is sensitive (error about sqrt(machine epsilon)
// times p), but then the strain below hardly depends on them (see there). The smallest is taken from det b = det(F)^2 instead, which keeps it to relative
// round-off for nearly flat F; two small ones are left to the eigen-solver (`accurate`).
//
// log b as a polynomial in b: Newton's interpolation of log at the eigenvalues a >= b' [>= c],
//   log b = log(a) I + log[a, b'] (b - a I) [+ log[a, b', c] (b - a I)(b - b' I)],
// exact for any symmetric b with those eigenvalues (it maps each eigenvalue to its log).
// - 2D: log[a, b'] = (log a - log b') / (a - b') (1 / b' when equal): its round-off, divided by
//   a - b', is multiplied by b - a I, of size a - b'.
// - 3D: log[x, y] = log1p((x - y) / y) / (x - y) (1 / y when equal), without cancellation, and
//   log[a, b', c] from its Taylor series about b' when a - c < 1e-4 c (error (1e-4)^3 relative),
//   otherwise (log[a, b'] - log[b', c]) / (a - c), whose round-off is multiplied by
//   (b - a I)(b - b' I), of size (a - c)^2.
// The result's error stays at round-off of |log b| also where eigenvalues meet or nearly do
// (tested against the SVD).
#include <algorithm>
#include <cmath>
#include <limits>

#include "solvers/mpm2grid/materials/polar_svd.hpp"

namespace suite::mpm2grid {

// The eigenvalues of b = F F^T and the principal log-stretches, both descending.
template <int Dim>
struct StretchSpectrum {
  Matrix<Dim> b;
  Vector<Dim> lambda;     // eigenvalues of b (sigma^2)
  Vector<Dim> log_sigma;  // log(sigma) = log(lambda) / 2; NaN when det F <= 0 (inverted)
  // False where the closed form loses digits: in 3D with two eigenvalues far below the third
  // (log V's error grows as about 1e-2 eps (lambda_1 / lambda_2)^2: 8e-9 at lambda_2 = 2.5e-5
  // lambda_1, 7e-4 at 1e-7). Below lambda_2 = 1e-2 lambda_1 (a stretch under a tenth of the
  // largest, far beyond any elastic soil state) callers take the eigen-solver (left_stretch).
  bool accurate = true;
};

// The spectra of N deformation gradients, computed stage by stage across them (the entries of b,
// the square roots, acos, sincos, the logs): each particle's chain of dependent operations is
// long, and the N chains overlap. Each spectrum gets the same operations
// as alone (stretch_spectrum).
template <int Dim, int N>
void stretch_spectra(const Matrix<Dim>* F, StretchSpectrum<Dim>* s) {
  static_assert(Dim == 2 || Dim == 3, "material models are written for 2 or 3 dimensions");
  // top: the largest eigenvalue; middle: in 3D the middle one. m = tr(b) / Dim; p: in 3D the
  // deviator's p (first its square), in 2D the radius of the eigenvalues about m (first its
  // square); 3D: det(b - m I) and the angle phi.
  double det[N], top[N], middle[N], m[N], p[N], det_dev[N], phi[N];
  for (int n = 0; n < N; ++n) {
    // b = F F^T, exactly symmetric: the upper triangle's row products, mirrored. Here and below
    // scalar code on the symmetric entries (faster than Eigen's products, squaredNorm and
    // determinant of the full matrices: docs/mpm2grid.md, "Benchmarks").
    Matrix<Dim>& b = s[n].b;
    for (int i = 0; i < Dim; ++i)
      for (int j = i; j < Dim; ++j) {
        double v = F[n](i, 0) * F[n](j, 0);
        for (int k = 1; k < Dim; ++k) v += F[n](i, k) * F[n](j, k);
        b(i, j) = b(j, i) = v;
      }
    det[n] = F[n].determinant();
    if constexpr (Dim == 2) {
      const double e = 0.5 * (b(0, 0) - b(1, 1));
      m[n] = 0.5 * (b(0, 0) + b(1, 1));
      p[n] = e * e + b(0, 1) * b(0, 1);
    } else {
      m[n] = (b(0, 0) + b(1, 1) + b(2, 2)) * (1.0 / 3);
      // The deviator b - m I: its diagonal d, its off-diagonal entries those of b.
      const double d0 = b(0, 0) - m[n], d1 = b(1, 1) - m[n], d2 = b(2, 2) - m[n];
      const double o01 = b(0, 1), o02 = b(0, 2), o12 = b(1, 2);
      p[n] = (d0 * d0 + d1 * d1 + d2 * d2 + 2 * (o01 * o01 + o02 * o02 + o12 * o12)) * (1.0 / 6);
      det_dev[n] = d0 * (d1 * d2 - o12 * o12) - o01 * (o01 * d2 - o12 * o02) + o02 * (o01 * o12 - d1 * o02);
    }
  }
  for (int n = 0; n < N; ++n) p[n] = std::sqrt(p[n]);
  if constexpr (Dim == 2) {
    for (int n = 0; n < N; ++n) top[n] = m[n] + p[n];
  } else {
    for (int n = 0; n < N; ++n)
      phi[n] = p[n] > 0 ? std::acos(std::clamp(det_dev[n] / (2 * p[n] * p[n] * p[n]), -1.0, 1.0)) / 3 : 0.0;
    for (int n = 0; n < N; ++n) {
      double bottom = m[n];
      top[n] = m[n];
      if (p[n] > 0) {
        // cos(phi + 2 pi / 3) = -(cos(phi) + sqrt(3) sin(phi)) / 2: one sincos for both, and a
        // sum of non-negative terms (phi in [0, pi / 3]).
        const double cos_phi = std::cos(phi[n]), sin_phi = std::sin(phi[n]);
        top[n] = m[n] + 2 * p[n] * cos_phi;
        bottom = m[n] - p[n] * (cos_phi + std::sqrt(3.0) * sin_phi);
      }
      middle[n] = 3 * m[n] - top[n] - bottom;
    }
  }
  // The smallest from det b = det(F)^2, with log(top middle) = log(top) + log(middle).
  for (int n = 0; n < N; ++n) {
    const double rest = Dim == 2 ? top[n] : top[n] * middle[n];
    const double log_top = std::log(top[n]);
    double log_rest = log_top;
    s[n].lambda[0] = top[n];
    s[n].log_sigma[0] = 0.5 * log_top;
    if constexpr (Dim == 3) {
      const double log_middle = std::log(middle[n]);
      s[n].lambda[1] = middle[n];
      s[n].log_sigma[1] = 0.5 * log_middle;
      s[n].accurate = middle[n] > 1e-2 * top[n];
      log_rest += log_middle;
    }
    s[n].lambda[Dim - 1] = det[n] * det[n] / rest;
    s[n].log_sigma[Dim - 1] = det[n] > 0 ? std::log(det[n]) - 0.5 * log_rest : std::numeric_limits<double>::quiet_NaN();
  }
}

template <int Dim>
StretchSpectrum<Dim> stretch_spectrum(const Matrix<Dim>& F) {
  StretchSpectrum<Dim> s;
  stretch_spectra<Dim, 1>(&F, &s);
  return s;
}

// log V = log(b) / 2 (the Hencky strain tensor) of N spectra with det F > 0, stage by stage
// across them as stretch_spectra (in 3D the log1p calls of all N, then the rest); each gets the
// same operations as alone (log_left_stretch).
template <int Dim, int N>
void log_left_stretches(const StretchSpectrum<Dim>* s, Matrix<Dim>* out) {
  const Matrix<Dim> I = Matrix<Dim>::Identity();
  if constexpr (Dim == 2) {
    for (int n = 0; n < N; ++n) {
      const double a = s[n].lambda[0], b = s[n].lambda[1];
      const double ab = a == b ? 1 / b : 2 * (s[n].log_sigma[0] - s[n].log_sigma[1]) / (a - b);
      out[n] = 0.5 * (2 * s[n].log_sigma[0] * I + ab * (s[n].b - a * I));
    }
  } else {
    // log[x, y] for (x, y) = (a, b') and (b', c): log1p((x - y) / y) / (x - y), 1 / y when equal.
    double first[2][N];
    for (int k = 0; k < 2; ++k)
      for (int n = 0; n < N; ++n) {
        const double x = s[n].lambda[k], y = s[n].lambda[k + 1];
        first[k][n] = x == y ? 1 / y : std::log1p((x - y) / y) / (x - y);
      }
    for (int n = 0; n < N; ++n) {
      const double a = s[n].lambda[0], b = s[n].lambda[1], c = s[n].lambda[2];
      const double ab = first[0][n];
      double abc;
      if (std::abs(a - c) < 1e-4 * c) {
        // log''/2 + log'''/6 (u + v) + log''''/24 (u^2 + u v + v^2) about b, u = a - b, v = c - b
        const double u = a - b, v = c - b, ib = 1 / b;
        abc = ib * ib * (-0.5 + ib * ((u + v) / 3 - ib * (u * u + u * v + v * v) / 4));
      } else {
        abc = (ab - first[1][n]) / (a - c);
      }
      // 0.5 (2 log sigma_0 I + ab A + abc A B), A = b - a I, B = b - b' I: A and B commute, so
      // A B is symmetric; its upper triangle, mirrored.
      Matrix<3> A = s[n].b, B = s[n].b;
      for (int i = 0; i < 3; ++i) A(i, i) -= a, B(i, i) -= b;
      for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j) {
          const double AB = A(i, 0) * B(0, j) + A(i, 1) * B(1, j) + A(i, 2) * B(2, j);
          out[n](i, j) = out[n](j, i) = 0.5 * ((i == j ? 2 * s[n].log_sigma[0] : 0.0) + ab * A(i, j) + abc * AB);
        }
    }
  }
}

template <int Dim>
Matrix<Dim> log_left_stretch(const StretchSpectrum<Dim>& s) {
  Matrix<Dim> out;
  log_left_stretches<Dim, 1>(&s, &out);
  return out;
}

}  // namespace suite::mpm2grid
