#pragma once
// The time-integrated state of an mpm2grid run in a checkpoint (core/checkpoint): every particle
// array of both species, the outflow record, the inlet's state, and the run's progress (time, step, the next sample
// and output times, counters). Everything a restart needs to continue bit for bit on the same rank
// count: the grid is rebuilt from the particles each step and holds nothing across steps.
#include <limits>
#include <map>
#include <string>

#include "core/checkpoint/checkpoint.hpp"
#include "solvers/mpm2grid/boundary/outlet_record.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"

namespace suite::mpm2grid {

// What the run loop carries between steps besides the simulation.
struct RunProgress {
  double next_sample = 0, next_output = 0;     // s
  double smallest_dt = 0;                      // s
  long long files = 0;                         // particle files written
  std::map<std::string, long long> limiters;   // steps limited by each criterion
  OutletRecord outlet;                         // the outflow discharge at the series times
  double initial_soil_volume = 0;              // V_0 of the eroded volume (io/dam_measures.hpp)
  // s: the implicit forces' step cap after a failed solve (run/run_mpm.cpp); infinity: none
  double dt_cap = std::numeric_limits<double>::infinity();
};

template <int Dim>
void write_state(checkpoint::Writer& w, const Simulation<Dim>& sim, const RunProgress& progress);

// Replaces the simulation's particles, time, step count, outflow record and inlet state, and the progress,
// with the checkpoint's. COLLECTIVE.
template <int Dim>
void read_state(checkpoint::Reader& r, Simulation<Dim>& sim, RunProgress& progress);

}  // namespace suite::mpm2grid
