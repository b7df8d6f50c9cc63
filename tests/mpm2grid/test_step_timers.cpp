// The step's phase timers (model/step_timers.hpp): the CPU clock beside the wall clock. A phase's
// CPU time is the calling thread's time on a core outside the MPI waits, so a sleeping thread
// adds wall time and no CPU time, and the CPU a wait burns (MPI's polling) counts as the wait's.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "solvers/mpm2grid/model/step_timers.hpp"

namespace suite::mpm2grid {
namespace {

// Runs on the calling thread until its CPU clock has advanced by `seconds`.
void spin_cpu(double seconds) {
  const double until = thread_cpu_seconds() + seconds;
  volatile double x = 0;
  while (thread_cpu_seconds() < until) x = x + 1;
}

// A thread asleep is off the CPU: entering and leaving the sleep take microseconds, so 5 ms of
// CPU over a 50 ms sleep would be a clock mixed up with the wall clock.
TEST(StepTimers, SleepCountsOnTheWallClockOnly) {
  StepTimes t;
  {
    StepPhaseScope scope(t, StepPhase::grid, nullptr);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const auto k = static_cast<std::size_t>(StepPhase::grid);
  EXPECT_GE(t.seconds[k], 0.05);
  EXPECT_GE(t.cpu[k], 0.0);
  EXPECT_LT(t.cpu[k], 0.005);
}

// Work on the thread is on its CPU clock, and never more of it than the wall clock saw (the CPU
// reads lie inside the wall reads).
TEST(StepTimers, WorkCountsOnBothClocks) {
  StepTimes t;
  {
    StepPhaseScope scope(t, StepPhase::g2p_soil, nullptr);
    spin_cpu(0.03);
  }
  const auto k = static_cast<std::size_t>(StepPhase::g2p_soil);
  EXPECT_GE(t.cpu[k], 0.03);
  EXPECT_LE(t.cpu[k], t.seconds[k]);
}

// What a wait burns on the CPU (a busy wait, as MPI's polling is) is the wait's, not the phase's
// own work: 30 ms spun inside the wait clock, 20 ms slept outside it leave the phase's own CPU
// near zero, its wait at least 30 ms and the wait clock's CPU at least 30 ms.
TEST(StepTimers, WaitsCpuIsTakenOffThePhase) {
  StepTimes t;
  WaitClock wait;
  {
    StepPhaseScope scope(t, StepPhase::halo_sum, &wait);
    wait.time([] { spin_cpu(0.03); });
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const auto k = static_cast<std::size_t>(StepPhase::halo_sum);
  EXPECT_GE(wait.cpu, 0.03);
  EXPECT_GE(t.waited[k], 0.03);
  EXPECT_GE(t.seconds[k], t.waited[k] + 0.02);
  EXPECT_GE(t.cpu[k], -1e-6);
  EXPECT_LT(t.cpu[k], 0.005);
  EXPECT_LE(t.cpu[k], t.seconds[k] - t.waited[k] + 1e-6);
}

}  // namespace
}  // namespace suite::mpm2grid
