#pragma once
// Seconds a rank spends blocked in the decomposition's MPI calls (MPI_Waitall on halo and
// migration messages, the collectives of the block claims and the halo plan), summed: the part
// of a phase that waits for other ranks rather than working (model/step_timers.hpp reports it).
#include <chrono>
#include <utility>

namespace suite::mpm2grid {

struct WaitClock {
  double seconds = 0;

  // Runs f() and counts its time as waiting; returns what f returns.
  template <class F>
  decltype(auto) time(F&& f) {
    struct Add {
      double& total;
      std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
      ~Add() { total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); }
    } add{seconds};
    return std::forward<F>(f)();
  }
};

}  // namespace suite::mpm2grid
