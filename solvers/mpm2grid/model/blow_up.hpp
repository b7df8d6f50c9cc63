#pragma once
// When a run has blown up (docs/methods/mpm2grid.md, "Output and restart": a NaN or an energy blow-up
// stops the run). Particles start at rest, so a particle can only move as fast as falling
// through the whole domain and the inflow make it: v_phys = sqrt(v_in^2 + 2 g H), H the domain's
// height along gravity, v_in the inlet's velocity at the time. A particle kFactor times faster
// holds kFactor^2 = 100 times the kinetic energy per unit mass any physical path gives it: an
// energy blow-up (an explicit drag past dt = 2 tau_d, a time step past stability), caught long
// before the state turns non-finite. The bound never falls below h / dt_max, the speed the
// time-step control is built for, so scenes without gravity or inflow keep a sensible scale.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "solvers/mpm2grid/model/simulation.hpp"

namespace suite::mpm2grid {

struct BlowUpCheck {
  static constexpr double kFactor = 10.0;

  // The largest speed a particle may have at time t before the run counts as blown up, m/s.
  template <int Dim>
  static double speed_limit(const SimulationSettings<Dim>& s, double inlet_velocity) {
    double height = 0.0;
    for (int d = 0; d < Dim; ++d) height += std::abs(s.gravity[d]) * (s.walls.hi[d] - s.walls.lo[d]);
    const double physical = std::sqrt(inlet_velocity * inlet_velocity + 2.0 * height);
    return kFactor * std::max(physical, s.h / s.dt_max);
  }
};

// The first particle whose state is not finite, or the fastest one, of a species.
template <int Dim>
struct ParticleScan {
  bool finite = true;
  std::size_t index = 0;  // the non-finite particle, else the fastest
  double speed = 0.0;     // m/s, of the fastest (when all are finite)

  // With threads, each scans parts of kPart particles and the parts' results are taken in order:
  // the same particle as one scan (the first of equally fast ones).
  static ParticleScan of(const Particles<Dim>& P, int threads = 1) {
    if (threads == 1) return of(P, {0, P.size()});
    std::vector<ParticleScan> parts((P.size() + kPart - 1) / kPart);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::size_t k = 0; k < parts.size(); ++k) parts[k] = of(P, {k * kPart, std::min(P.size(), (k + 1) * kPart)});
    ParticleScan s;
    for (const ParticleScan& part : parts) {
      if (!part.finite) return part;
      if (part.speed > s.speed) s = part;
    }
    return s;
  }

 private:
  static ParticleScan of(const Particles<Dim>& P, ParticleRun run) {
    ParticleScan s;
    double fastest2 = -1.0;
    for (std::size_t p = run.begin; p < run.end; ++p) {
      if (!P.x[p].allFinite() || !P.v[p].allFinite()) {
        s.finite = false;
        s.index = p;
        return s;
      }
      const double v2 = P.v[p].squaredNorm();
      if (v2 > fastest2) fastest2 = v2, s.index = p;
    }
    s.speed = fastest2 > 0 ? std::sqrt(fastest2) : 0.0;
    return s;
  }
};

}  // namespace suite::mpm2grid
