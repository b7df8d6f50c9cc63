#pragma once
// The running maximum of a quantity q(t) and its time, with golden-section refinement on a
// continuous representation of q over a bracket (the integrator passes its dense output, so the
// peak outflow and its time do not depend on where the steps fall; simulate.cpp decides which
// brackets hold a maximum).
#include <cmath>

namespace suite::breach {

class PeakSearch {
 public:
  void sample(double t, double q) {
    if (q > value_) value_ = q, time_ = t;
  }
  // Maximises q over [a, b] (q unimodal there). The bracket shrinks by 0.618 per evaluation;
  // 60 take it to 3e-13 of its size.
  template <class Q>
  void search(const Q& q, double a, double b) {
    const double r = (std::sqrt(5.0) - 1.0) / 2.0;
    double x1 = b - r * (b - a), x2 = a + r * (b - a), f1 = q(x1), f2 = q(x2);
    for (int i = 0; i < 60 && b - a > 1e-12 * std::abs(b); ++i) {
      if (f1 < f2) {
        a = x1, x1 = x2, f1 = f2, x2 = a + r * (b - a), f2 = q(x2);
      } else {
        b = x2, x2 = x1, f2 = f1, x1 = b - r * (b - a), f1 = q(x1);
      }
    }
    sample(x1, f1);
    sample(x2, f2);
  }
  double value() const { return value_; }
  double time() const { return time_; }

 private:
  double value_ = -1.0, time_ = 0.0;
};

}  // namespace suite::breach
