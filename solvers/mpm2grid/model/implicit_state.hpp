#pragma once
// What the implicit forces (model/implicit_forces.cpp) keep between the residual evaluations of
// one step's Newton solve, and the solve's counts. Scratch: rebuilt every step.
#include <stdexcept>
#include <vector>

#include "core/petsc/newton_krylov.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"

namespace suite::mpm2grid {

// The elastic forces of both species (the water's pressure, the soil's elastic stress) in the
// grid update: at the step's start (explicit: dt limited by the wave speeds) or at its end,
// backward Euler (the dissertation's eq. 3.24, a Newton-Krylov solve each step; dt limited by
// the particles' speed).
enum class ForceScheme { explicit_start, implicit_end };

// A step's Newton-Krylov solve did not converge. Thrown on every rank before the step changed any
// state that a second try with a smaller dt would not set again (run/run_mpm.cpp retries).
class ImplicitSolveFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <int Dim>
struct ImplicitState {
  // The unknowns: this rank's owned node slots with soil mass, then with water mass, Dim
  // velocity components each.
  std::vector<long> soil_slots, water_slots;
  // The node forces that do not depend on the velocities (the soil's loads; the rest went into
  // the momentum sums with dt).
  std::vector<Vec<Dim>> soil_base, water_base;
  // The particles' positions and mass-free copies whose G2P gives grad v at the trial velocities
  // and whose P2G spreads only the stresses (their mass, velocity and C are zero).
  Particles<Dim> soil_probe, water_probe;
  std::vector<Mat<Dim>> soil_trial;    // F^ per soil particle
  std::vector<Mat<Dim>> soil_stress;   // tau(F^) (I + dt grad v)^-T per soil particle, Pa
  std::vector<double> water_pressure;  // J^ p(J^) per water particle (Kirchhoff), Pa
  std::vector<double> water_trial_J;   // J^ per water particle
  // The water's tension clamp as an active set: 1 where a particle's pressure is held at
  // min_pressure for the whole Newton solve, 0 where it follows the unclamped law (the clamp's
  // kink inside the solve stalls Newton).
  std::vector<char> water_held;
  // 1 for the soil particles the excess-stress erosion detached (suspended) at the step's start:
  // they carry no stress in the solve, as in the particle update.
  std::vector<char> stress_free;
  NodeFields<Dim> soil_force, water_force;  // the stresses' node forces, N
  NewtonKrylovStats last;                   // the last step's last solve
  int passes = 0;                           // the last step's clamp passes (solves)
  long long passes_total = 0;
  // With clamp_passes > 1: the steps where some particle still ended on the other side of the
  // clamp than held.
  long long clamp_changed_steps = 0;
  // Since the simulation was built (the evaluations with the first guess's and the passes').
  long long newton_total = 0, krylov_total = 0, evaluations_total = 0;
  int newton_most = 0, krylov_most = 0;  // the most of one step
};

}  // namespace suite::mpm2grid
