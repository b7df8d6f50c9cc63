// The Dormand-Prince 5(4) step and its dense output on an ODE with a known solution,
// y' = [y1, -y0] (a rotation: y = (sin t, cos t)): the step is 5th order, the error estimate
// 4th-order accurate, and the continuous extension 4th order anywhere inside the step.
#include <gtest/gtest.h>

#include <cmath>

#include "solvers/breach/model/dormand_prince.hpp"

namespace {

using suite::breach::dormand_prince_step;
using Vec = std::array<double, 2>;

auto rotation = [](double, const Vec& y, Vec& dy) {
  dy[0] = y[1];
  dy[1] = -y[0];
};

// Largest error of the step end and of the dense output at several theta, for step h from t = 0.3.
std::pair<double, double> errors(double h) {
  const double t = 0.3;
  const Vec y0{std::sin(t), std::cos(t)};
  Vec k1;
  rotation(t, y0, k1);
  const auto s = dormand_prince_step<2>(rotation, t, y0, k1, h);
  const double end = std::hypot(s.y[0] - std::sin(t + h), s.y[1] - std::cos(t + h));
  double dense = 0.0;
  for (double theta : {0.1, 0.37, 0.5, 0.81}) {
    const Vec y = s.at(theta);
    dense = std::max(dense, std::hypot(y[0] - std::sin(t + theta * h), y[1] - std::cos(t + theta * h)));
  }
  EXPECT_EQ(s.at(0.0), y0);
  EXPECT_NEAR(s.at(1.0)[0], s.y[0], 1e-15);
  return {end, dense};
}

TEST(DormandPrince, OrdersOfStepAndDenseOutput) {
  const auto [e1, d1] = errors(0.2);
  const auto [e2, d2] = errors(0.1);
  // Local error of a p-th order step shrinks as h^(p+1): 5th-order step -> 2^6 = 64 per halving,
  // 4th-order dense output -> 2^5 = 32 (ratios within a factor ~1.5 of the asymptotic ones).
  EXPECT_GT(e1 / e2, 40.0) << e1 << " " << e2;
  EXPECT_GT(d1 / d2, 20.0) << d1 << " " << d2;
  EXPECT_LT(d2, 1e-7);
}

}  // namespace
