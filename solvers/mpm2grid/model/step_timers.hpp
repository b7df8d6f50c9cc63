#pragma once
// Where a step's time goes, per rank (issue 28): the wall-clock seconds of each phase of
// Simulation::step() summed over the steps, and of each the part spent blocked in MPI calls
// (the decomposition's WaitClock: waiting for messages and collectives, i.e. for other ranks).
// run.json reports them as phases "step/<name>" and "step/<name>/wait" with min, mean and max
// over the ranks (core/run/phase_timers.hpp), so a scaling table explains itself: a phase whose
// max is far above its mean is imbalanced, a phase whose wait is most of its time waits for the
// slowest rank. And "step/<name>/cpu": the CPU seconds of the rank's main thread in the phase
// outside its waits. A phase's own wall time (seconds - waited) less that CPU time is the time
// the thread was off its core (another process, a virtual machine's host): where the slowest
// rank of a phase spent its extra time off its core, the partition did not give it more work.
#include <array>
#include <cstddef>

#include "solvers/mpm2grid/decomposition/wait_clock.hpp"

namespace suite::mpm2grid {

enum class StepPhase : int {
  balance,     // the load check and, when due, METIS and the migration of all particles
  grid,        // the sparse grid of this step's stencils, particles put back in group order
  halo_plan,   // claiming new blocks, the halo plan (who sends which ghost blocks)
  stresses,    // the particles' stresses, drag and solid volumes
  p2g_water,   // the water's P2G
  halo_sum,    // reverse halo sums of both species, the water's node pressure to the ghosts
  p2g_soil,    // the soil's P2G (with the buoyancy and loads)
  grid_solve,  // the drag-coupled grid velocities (lumped, explicit or the PETSc solve)
  boundary,    // walls and the inlet's velocities on the grid
  halo_copy,   // the forward halo copy of the velocities
  g2p_water,   // the water's G2P and move
  g2p_soil,    // the soil's G2P, move and return mapping
  outflow,     // particles leaving through open sides, the outflow record
  inlet,       // the inlet's new particles
  migrate,     // particles to the owners of their new home blocks
  bed_shear,   // the bed-shear closure's columns (two reductions over them) and the erosion
};
inline constexpr std::size_t kStepPhases = 16;
inline constexpr std::array<const char*, kStepPhases> kStepPhaseNames{
    "balance", "grid",     "halo plan",  "stresses", "p2g water", "halo sum", "p2g soil", "grid solve",
    "boundary", "halo copy", "g2p water", "g2p soil", "outflow",   "inlet",    "migrate",
    "bed shear"};

struct StepTimes {
  std::array<double, kStepPhases> seconds{};  // per phase, summed over the steps
  std::array<double, kStepPhases> waited{};   // of those, blocked in MPI calls
  std::array<double, kStepPhases> cpu{};      // the main thread's CPU seconds outside those calls
};

// Adds the time of one scope to a phase, what a wait clock (nullptr on one rank) counted
// meanwhile to the phase's wait, and the calling thread's CPU time outside the wait clock's
// calls to the phase's cpu. Constructed and destroyed on the rank's main thread.
class StepPhaseScope {
 public:
  StepPhaseScope(StepTimes& times, StepPhase phase, const WaitClock* wait)
      : times_(times),
        phase_(static_cast<std::size_t>(phase)),
        wait_(wait),
        wait_start_(wait ? wait->seconds : 0.0),
        wait_cpu_start_(wait ? wait->cpu : 0.0) {}
  ~StepPhaseScope() {
    const auto spans = start_.since();
    double cpu = spans.cpu;
    times_.seconds[phase_] += spans.wall;
    if (wait_) {
      times_.waited[phase_] += wait_->seconds - wait_start_;
      cpu -= wait_->cpu - wait_cpu_start_;
    }
    times_.cpu[phase_] += cpu;
  }
  StepPhaseScope(const StepPhaseScope&) = delete;
  StepPhaseScope& operator=(const StepPhaseScope&) = delete;

 private:
  StepTimes& times_;
  std::size_t phase_;
  const WaitClock* wait_;
  double wait_start_;
  double wait_cpu_start_;
  ClockMark start_;
};

}  // namespace suite::mpm2grid
