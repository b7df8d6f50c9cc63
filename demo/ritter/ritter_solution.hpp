#pragma once
// Ritter's (1892) solution of the shallow-water equations for the instantaneous break of a
// dam holding still water of depth h0 over a dry, horizontal, frictionless bed; the dam is at
// x = 0 and the reservoir at x < 0. With c0 = sqrt(g h0) and xi = x / t:
//   xi <= -c0        h = h0,                     u = 0             (undisturbed reservoir)
//   -c0 < xi < 2 c0  h = (2 c0 - xi)^2 / (9 g),  u = 2/3 (c0 + xi) (rarefaction fan)
//   xi >= 2 c0       h = 0,                      u = 0             (dry bed ahead of the front)
// At the dam h = 4/9 h0 and u = 2/3 c0, so the discharge per unit width is (8/27) sqrt(g) h0^1.5
// for every t > 0. The solution holds in a reservoir of length L until the negative wave
// reaches its back wall, t <= L / c0. Units: SI (m, s, m/s).
namespace suite::demo {

struct ShallowWaterState {
  double depth = 0.0;     // h, m
  double velocity = 0.0;  // u, m/s
};

class RitterSolution {
 public:
  RitterSolution(double h0, double gravity);
  ShallowWaterState at(double x, double t) const;
  double wave_speed() const { return c0_; }                        // c0, m/s
  double front_position(double t) const { return 2.0 * c0_ * t; }  // m
  double unit_discharge_at_dam() const;                            // m^2/s

 private:
  double h0_, g_, c0_;
};

}  // namespace suite::demo
