#pragma once
// One step of the Dormand-Prince 5(4) pair (Dormand & Prince 1980; coefficients as in Hairer,
// Norsett & Wanner, Solving ODEs I, Table 5.2): the 5th-order solution, the difference to the
// embedded 4th-order one (the local error estimate), and the derivative at the end (first same
// as last, so an accepted step costs six evaluations).
#include <array>
#include <cstddef>

namespace suite::breach {

template <std::size_t N>
struct DormandPrinceStep {
  using Vec = std::array<double, N>;
  Vec y;      // solution at t + h
  Vec error;  // y5 - y4
  Vec f_end;  // f(t + h, y)
  // Dense output (Hairer, Norsett & Wanner, sec. II.6; the continuous extension of DOPRI5):
  // y(t + theta h) = r0 + theta (r1 + (1 - theta) (r2 + theta (r3 + (1 - theta) r4))), 4th order.
  std::array<Vec, 5> r;
  Vec at(double theta) const {
    Vec out;
    const double u = 1.0 - theta;
    for (std::size_t i = 0; i < N; ++i)
      out[i] = r[0][i] + theta * (r[1][i] + u * (r[2][i] + theta * (r[3][i] + u * r[4][i])));
    return out;
  }
};

// f(t, y, dydt). k1 = f(t, y0).
template <std::size_t N, class F>
DormandPrinceStep<N> dormand_prince_step(F&& f, double t, const std::array<double, N>& y0,
                                         const std::array<double, N>& k1, double h) {
  using Vec = std::array<double, N>;
  static constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
  static constexpr double a21 = 1.0 / 5;
  static constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
  static constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
  static constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
  static constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                          a65 = -5103.0 / 18656;
  static constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784, b6 = 11.0 / 84;
  // e = b - b*, the 5th minus the 4th-order weights.
  static constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                          e6 = 22.0 / 525, e7 = -1.0 / 40;
  Vec k2, k3, k4, k5, k6, tmp;
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y0[i] + h * a21 * k1[i];
  f(t + c2 * h, tmp, k2);
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y0[i] + h * (a31 * k1[i] + a32 * k2[i]);
  f(t + c3 * h, tmp, k3);
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y0[i] + h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
  f(t + c4 * h, tmp, k4);
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y0[i] + h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
  f(t + c5 * h, tmp, k5);
  for (std::size_t i = 0; i < N; ++i)
    tmp[i] = y0[i] + h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
  f(t + h, tmp, k6);
  DormandPrinceStep<N> out;
  for (std::size_t i = 0; i < N; ++i)
    out.y[i] = y0[i] + h * (b1 * k1[i] + b3 * k3[i] + b4 * k4[i] + b5 * k5[i] + b6 * k6[i]);
  f(t + h, out.y, out.f_end);
  for (std::size_t i = 0; i < N; ++i)
    out.error[i] = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * out.f_end[i]);
  static constexpr double d1 = -12715105075.0 / 11282082432.0, d3 = 87487479700.0 / 32700410799.0,
                          d4 = -10690763975.0 / 1880347072.0, d5 = 701980252875.0 / 199316789632.0,
                          d6 = -1453857185.0 / 822651844.0, d7 = 69997945.0 / 29380423.0;
  for (std::size_t i = 0; i < N; ++i) {
    const double dy = out.y[i] - y0[i], b = h * k1[i] - dy;
    out.r[0][i] = y0[i];
    out.r[1][i] = dy;
    out.r[2][i] = b;
    out.r[3][i] = dy - h * out.f_end[i] - b;
    out.r[4][i] = h * (d1 * k1[i] + d3 * k3[i] + d4 * k4[i] + d5 * k5[i] + d6 * k6[i] + d7 * out.f_end[i]);
  }
  return out;
}

}  // namespace suite::breach
