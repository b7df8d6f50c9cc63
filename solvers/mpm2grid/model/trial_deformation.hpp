#pragma once
// The trial deformation gradient (I + dt grad v) F as F + dt (grad v F), in scalar code (faster
// than Eigen's product with the sum: docs/mpm2grid.md, "Benchmarks"). The particle update and the
// implicit forces' residual (model/implicit_forces.cpp) both form it.
#include "solvers/mpm2grid/kernels/bspline.hpp"

namespace suite::mpm2grid {

template <int Dim>
Mat<Dim> trial_deformation(const Mat<Dim>& grad_v, const Mat<Dim>& F, double dt) {
  Mat<Dim> out;
  for (int j = 0; j < Dim; ++j)
    for (int i = 0; i < Dim; ++i) {
      double v = grad_v(i, 0) * F(0, j);
      for (int k = 1; k < Dim; ++k) v += grad_v(i, k) * F(k, j);
      out(i, j) = F(i, j) + dt * v;
    }
  return out;
}

}  // namespace suite::mpm2grid
