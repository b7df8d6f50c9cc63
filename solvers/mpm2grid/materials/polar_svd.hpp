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
#include <Eigen/LU>  // determinant()
#include <Eigen/SVD>

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

}  // namespace suite::mpm2grid
