#pragma once
// Seconds a rank spends blocked in the decomposition's MPI calls (MPI_Waitall on halo and
// migration messages, the collectives of the block claims and the halo plan), summed: the part
// of a phase that waits for other ranks rather than working (model/step_timers.hpp reports it).
// Beside the wall clock, the CPU seconds of the calling thread over the same calls, so that a
// phase's own work can be told from its waits on the CPU clock too.
#include <chrono>
#include <ctime>
#include <utility>

namespace suite::mpm2grid {

// CPU seconds the calling thread has run (CLOCK_THREAD_CPUTIME_ID), about 0.4 us a call. Against
// the wall clock over the same span it gives the time the thread was ready but off its core:
// another process on the core or, in a virtual machine, the host's steal (Linux's paravirtual
// steal clock keeps it out of the thread's run time).
inline double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// A moment on both clocks, and the seconds since on each: the CPU span is read inside the wall
// span (taken after the wall's start, before its end), so it never exceeds it by the reads.
struct ClockMark {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  double cpu = thread_cpu_seconds();

  struct Spans {
    double wall, cpu;
  };
  Spans since() const {
    const double cpu_span = thread_cpu_seconds() - cpu;
    return {std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count(), cpu_span};
  }
};

struct WaitClock {
  double seconds = 0;  // wall
  double cpu = 0;      // the calling thread's CPU over the same calls (MPI's polling)

  // Runs f() and counts its time as waiting; returns what f returns.
  template <class F>
  decltype(auto) time(F&& f) {
    struct Add {
      WaitClock& clock;
      ClockMark start{};
      ~Add() {
        const auto spans = start.since();
        clock.seconds += spans.wall, clock.cpu += spans.cpu;
      }
    } add{*this};
    return std::forward<F>(f)();
  }
};

}  // namespace suite::mpm2grid
