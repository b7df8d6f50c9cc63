// Terzaghi's one-dimensional consolidation (docs/methods/mpm2grid.md, "Validation references") through
// the scene scenes/terzaghi.yaml and whole steps of the model with mixture: true: a saturated
// column of height H on an impermeable floor, drained at its top, loaded there by a surcharge
// sigma that grows linearly over t_r.
//
// Reference: the linear theory with compressible pore water (Biot) and incompressible grains,
//   dp/dt = B dsigma/dt + c_v d^2p/dz^2,   p = 0 at the top, dp/dz = 0 at the floor,
//   B = 1 / (1 + n E_oed / K_w),   c_v = k / (gamma_w (1 / E_oed + n / K_w)),
// with K_w = gamma k_water the water's bulk modulus, gamma_w = rho_w g0. For a step load the
// solution is Terzaghi's series u(z, t) = B sigma sum_m (2 / M) sin(M z / H) exp(-M^2 T_v),
// M = pi (2m + 1) / 2, T_v = c_v t / H^2, z the depth below the drained top; for the ramp,
// Duhamel's integral of it (exact, below). The settlement is (sigma H - int p dz) / E_oed.
//
// Measures, at T_v = 0.4 (the ramp's end), 0.6, 0.8 and 1.2, over two resolutions (before the
// ramp's end the column still rings with Biot's waves, which the quasi-static theory leaves
// out: at T_v = 0.2 its interior layers are within 8% of sigma):
// - the shortening of the column between its top and bottom rows of particles against the
//   reference over the same span, relative to the final settlement sigma H / E_oed. (The
//   bottom row is the reference point, not the floor: the slip floor stops motion into it but
//   not away from it, so what ringing is left lifts the column's foot by about 0.01 mm.)
// - the mean pore pressure of the water particles in each layer one cell high against the
//   reference at their depths, relative to sigma: its L1 norm over the depth (sum over the
//   layers of |error| h / H), and its largest value over the interior layers, more than two
//   cells from the drained top and from the floor. The layers next to the drained top carry
//   the B-spline's truncated support there: errors of up to 9% of sigma over three cells, so the
//   L1 norm converges at first order in h while the interior is within about 1%. (The floor's
//   layers, a slip wall with the mirror condition of boundary/wall_fold.hpp, are within 1.3%;
//   without it they were up to 20% off, as the hydrostatic tank's floor layer was.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/config/config.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"
#include "solvers/mpm2grid/scenes/scene.hpp"

namespace suite::mpm2grid {
namespace {

constexpr double kG0 = 9.80665;  // the drag's gamma_w uses standard gravity (SoilSettings)

// The reference for the scene's parameters.
struct Consolidation {
  double H, sigma, ramp, B, c_v, e_oed;

  template <int Dim>
  explicit Consolidation(const Scene<Dim>& sc) {
    const auto& s = sc.simulation;
    const auto& r = sc.soil_regions.at(0);
    H = r.hi[1] - r.lo[1];
    sigma = r.surcharge;
    ramp = s.load_ramp;
    e_oed = s.soil.material.lambda + 2 * s.soil.material.mu;
    const double n = s.soil.porosity, K_w = s.water.eos.effective_bulk_modulus();
    B = 1 / (1 + n * e_oed / K_w);
    c_v = s.soil.conductivity / (s.water.density * kG0 * (1 / e_oed + n / K_w));
  }

  // B sigma times the sum over the modes of f(M) and the load's time factor: Duhamel's integral
  // of the step response exp(-a (t - tau)), a = M^2 c_v / H^2, over the load's rate 1 / t_r for
  // 0 < tau < min(t, t_r) (the step itself without a ramp).
  template <class F>
  double series(double t, F&& f) const {
    double sum = 0;
    for (int m = 0; m < 400; ++m) {
      const double M = std::numbers::pi * (2 * m + 1) / 2, a = M * M * c_v / (H * H);
      const double time = ramp > 0 ? (std::exp(-a * (t - std::min(t, ramp))) - std::exp(-a * t)) / (a * ramp)
                                   : std::exp(-a * t);
      sum += f(M) * time;
    }
    return B * sigma * sum;
  }
  // Pore pressure at depth z below the top, Pa.
  double pressure(double z, double t) const {
    return series(t, [&](double M) { return 2 / M * std::sin(M * z / H); });
  }
  double load(double t) const { return sigma * (ramp > 0 ? std::min(1.0, t / ramp) : 1.0); }
  // Shortening of the column between the depths z1 < z2, m: the integral of (load - p) / E_oed.
  double shortening(double z1, double z2, double t) const {
    const double p = series(t, [&](double M) { return 2 * H / (M * M) * (std::cos(M * z1 / H) - std::cos(M * z2 / H)); });
    return (load(t) * (z2 - z1) - p) / e_oed;
  }
  double final_settlement() const { return sigma * H / e_oed; }
};

struct Errors {
  double shortening = 0;  // |shortening - reference| / final settlement
  double l1 = 0;          // sum over the layers of |layer mean of (p - p_ref)| / sigma h / H
  double interior = 0;    // largest |layer mean of (p - p_ref)| / sigma over the interior layers
};

// The errors at each T_v; `overrides` change the scene (e.g. to 3D).
template <int Dim>
std::vector<Errors> consolidate(double h, const std::vector<double>& times, std::vector<std::string> overrides = {}) {
  const std::string path = std::string(SUITE_SOURCE_DIR) + "/solvers/mpm2grid/scenes/terzaghi.yaml";
  overrides.push_back(fmt::format("grid.spacing={} m", h));
  auto sc = read_scene<Dim>(config::Config::from_file(path, overrides));
  const Consolidation ref(sc);
  Simulation<Dim> sim(sc.simulation);
  seed_particles(sc, sim);
  const auto& soil = sim.soil();
  // The top row carries the surcharge; the bottom row is the first lattice row.
  auto rows = [&] {
    double top = 0, bottom = 0;
    int n_top = 0, n_bottom = 0;
    for (std::size_t p = 0; p < soil.size(); ++p) {
      if (soil.load[p][1] < 0) top += soil.x[p][1], ++n_top;
      if (soil.x[p][1] < h / 2 && soil.load[p][1] == 0) bottom += soil.x[p][1], ++n_bottom;
    }
    EXPECT_EQ(n_top, n_bottom);
    return top / n_top - bottom / n_bottom;
  };
  const double length0 = rows();
  const double z1 = h / 4, z2 = ref.H - h / 4;  // depths of the two rows
  const int layers = static_cast<int>(std::lround(ref.H / h));

  std::vector<Errors> out;
  for (const double T_v : times) {
    const double t = T_v * ref.H * ref.H / ref.c_v;
    while (sim.time() < t) sim.step(std::min(sim.stable_dt().dt, t - sim.time()));
    Errors e;
    const double shortening = length0 - rows(), reference = ref.shortening(z1, z2, t);
    e.shortening = std::abs(shortening - reference) / ref.final_settlement();

    std::vector<double> sum(layers, 0.0);
    std::vector<int> count(layers, 0);
    const auto& w = sim.water();
    for (std::size_t p = 0; p < w.size(); ++p) {
      const double z = ref.H - w.x[p][1];
      if (z < 0 || z >= ref.H) continue;
      const int k = std::min(layers - 1, static_cast<int>(z / h));
      sum[k] += (sim.settings().water.eos.pressure(w.J[p]) - ref.pressure(z, t)) / ref.sigma, ++count[k];
    }
    for (int k = 0; k < layers; ++k) {
      if (!count[k]) continue;
      const double err = std::abs(sum[k] / count[k]);
      e.l1 += err * h / ref.H;
      if (k >= 3 && k < layers - 3) e.interior = std::max(e.interior, err);
    }
    std::printf("%dD, h = H/%d, T_v = %.1f: shortening %.4g mm (reference %.4g mm), error %.4f of the final settlement; "
                "pore pressure error L1 %.4f, interior layers at most %.4f of sigma\n",
                Dim, layers, T_v, 1e3 * shortening, 1e3 * reference, e.shortening, e.l1, e.interior);
    out.push_back(e);
  }
  return out;
}

TEST(Terzaghi, ConsolidationFollowsTheoryAndConvergesInH) {
  const std::vector<double> times{0.4, 0.6, 0.8, 1.2};
  const auto coarse = consolidate<2>(1.0 / 16, times), fine = consolidate<2>(1.0 / 32, times);
  for (std::size_t i = 0; i < times.size(); ++i) {
    SCOPED_TRACE(fmt::format("T_v = {}", times[i]));
    EXPECT_LT(fine[i].shortening, 0.02);
    EXPECT_LT(fine[i].interior, 0.03);
    EXPECT_LT(fine[i].l1, 0.03);
    // First order: halving h about halves the L1 norm; asked: at least a third less.
    EXPECT_LT(fine[i].l1, 0.67 * coarse[i].l1);
  }
}

// The same column in 3D, two cells wide in x and z between slip walls, at h = H/16: the mixture's
// J update, solid fractions (a node on an edge of the box has 1/4 of its weight inside) and
// wave speed in three dimensions (about 16 s). The 2D column at the same h measures L1 3.3% and
// interior 2.6% of sigma at T_v = 0.6, so 5% asks 3D to be as good as 2D with a margin for the
// coarse grid; the shortening is held to the 2D bound.
TEST(Terzaghi, ConsolidationIn3D) {
  const std::vector<double> times{0.6, 1.2};
  const double h = 1.0 / 16, w = 2 * h;
  const auto e = consolidate<3>(h, times, {"dimension=3", "domain.lo=[0, 0, 0]", fmt::format("domain.hi=[{}, 1.25, {}]", w, w),
                                          "soil.regions.0.box.lo=[0, 0, 0]",
                                          fmt::format("soil.regions.0.box.hi=[{}, 1.0, {}]", w, w)});
  for (std::size_t i = 0; i < times.size(); ++i) {
    SCOPED_TRACE(fmt::format("T_v = {}", times[i]));
    EXPECT_LT(e[i].shortening, 0.02);
    EXPECT_LT(e[i].interior, 0.05);
    EXPECT_LT(e[i].l1, 0.05);
  }
}

}  // namespace
}  // namespace suite::mpm2grid
