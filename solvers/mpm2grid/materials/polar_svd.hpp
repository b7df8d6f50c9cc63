#pragma once
// Singular value decomposition of a deformation gradient with proper rotations, as MPM
// constitutive models use it: F = U diag(sigma) V^T with det U = det V = +1.
//
// Eigen's JacobiSVD returns orthogonal U, V (each may be a reflection) and singular values
// sigma_0 >= sigma_1 >= ... >= 0. A reflection in U (or V) is turned into a rotation by negating
// its last column together with the last (smallest) singular value. So:
//   det F > 0  ->  all sigma_i > 0 (the usual case; log(sigma) is the principal Hencky strain);
//   det F < 0  ->  sigma_{Dim-1} < 0 (an inverted element; its Hencky strain is undefined and
//                  models that take log(sigma) return NaN, which the caller's stability
//                  check is meant to notice);
//   det F = 0  ->  sigma_{Dim-1} = 0.
// Dimensionless; the matrices are Dim x Dim, Dim = 2 or 3.
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>  // determinant()
#include <Eigen/SVD>
#include <limits>

namespace suite::mpm2grid {

// Fixed-size types of the material models. Same types as Mat<Dim> / Vec<Dim> of
// kernels/bspline.hpp, so the two mix freely.
template <int Dim>
using Matrix = Eigen::Matrix<double, Dim, Dim>;
template <int Dim>
using Vector = Eigen::Matrix<double, Dim, 1>;

template <int Dim>
struct RotationSvd {
  Matrix<Dim> U;      // rotation, det = +1
  Vector<Dim> sigma;  // singular values, descending in magnitude; only the last may be <= 0
  Matrix<Dim> V;      // rotation, det = +1
};

template <int Dim>
RotationSvd<Dim> rotation_svd(const Matrix<Dim>& F) {
  static_assert(Dim == 2 || Dim == 3, "material models are written for 2 or 3 dimensions");
  const Eigen::JacobiSVD<Matrix<Dim>> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  RotationSvd<Dim> r{svd.matrixU(), svd.singularValues(), svd.matrixV()};
  if (r.U.determinant() < 0) {
    r.U.col(Dim - 1) *= -1;
    r.sigma(Dim - 1) *= -1;
  }
  if (r.V.determinant() < 0) {
    r.V.col(Dim - 1) *= -1;
    r.sigma(Dim - 1) *= -1;
  }
  return r;
}

// The principal directions and log-stretches of a deformation gradient, as the Hencky model
// needs them: U of the SVD F = U diag(sigma) V^T (its columns only used as U (.) U^T) and
// log(sigma), from the left Cauchy-Green tensor b = F F^T = U diag(sigma^2) U^T.
// - 2D: in closed form. With e = (b00 - b11)/2, c = b01, r = |(e, c)|, the larger eigenvalue is
//   (b00 + b11)/2 + r and its direction at half the angle of (e, c), cos^2 = (r + e)/(2r),
//   sin^2 = (r - e)/(2r) (the one of r + e, r - e that cancels taken as c^2 over the other); the
//   smaller stretch from det F = sigma_0 sigma_1. Faster than the 2x2 JacobiSVD.
// - 3D: Eigen's SelfAdjointEigenSolver (Householder tridiagonalization and implicit QR; its 3x3
//   closed form loses digits of the stress where two stretches are equal, as in soil at rest),
//   faster than JacobiSVD; the smallest stretch again from det F.
// (What each choice measured: docs/mpm2grid.md, "Benchmarks".)
// Both agree with the SVD to round-off, also for equal stretches and for F nearly flat (tested).
// An inverted F (det F <= 0) has no Hencky strain: a log-stretch is then NaN, as the SVD's
// negative value gives.
template <int Dim>
struct LeftStretch {
  Matrix<Dim> U;
  Vector<Dim> log_sigma;
};

template <int Dim>
LeftStretch<Dim> left_stretch(const Matrix<Dim>& F) {
  if constexpr (Dim == 2) {
    const Matrix<2> b = F * F.transpose();
    const double e = 0.5 * (b(0, 0) - b(1, 1)), c = b(0, 1), r = std::sqrt(e * e + c * c);
    const double det = F.determinant();
    LeftStretch<2> s;
    if (r == 0) {
      s.U.setIdentity();
    } else {
      double p, q;  // r + e and r - e, the one without cancellation first (p q = c^2)
      if (e >= 0)
        p = r + e, q = c * c / p;
      else
        q = r - e, p = c * c / q;
      const double cos_t = std::sqrt(p / (2 * r)), sin_t = std::copysign(std::sqrt(q / (2 * r)), c);
      s.U << cos_t, -sin_t, sin_t, cos_t;
    }
    const double lambda1 = 0.5 * (b(0, 0) + b(1, 1)) + r;  // the larger eigenvalue; lambda2 = det^2 / lambda1
    s.log_sigma[0] = 0.5 * std::log(lambda1);
    s.log_sigma[1] = det > 0 ? std::log(det) - s.log_sigma[0] : std::numeric_limits<double>::quiet_NaN();
    return s;
  } else {
    const Eigen::SelfAdjointEigenSolver<Matrix<Dim>> eig(F * F.transpose());
    LeftStretch<Dim> s{eig.eigenvectors(), (0.5 * eig.eigenvalues().array().log()).matrix()};
    // The smallest eigenvalue (first: ascending) carries the absolute error of the largest; its
    // stretch from det F = sigma_0 sigma_1 sigma_2 instead keeps it to relative round-off.
    const double det = F.determinant();
    s.log_sigma[0] =
        det > 0 ? std::log(det) - s.log_sigma[1] - s.log_sigma[2] : std::numeric_limits<double>::quiet_NaN();
    return s;
  }
}

}  // namespace suite::mpm2grid
