#include "core/log/progress.hpp"

namespace suite {

ProgressLine::ProgressLine(Logger& log, double t_start, double t_end, double interval_seconds)
    : log_(log),
      t_start_(t_start),
      t_end_(t_end),
      interval_(interval_seconds),
      wall_start_(clock::now()),
      last_print_(wall_start_) {}

double ProgressLine::eta_seconds(double t) const {
  const double wall = std::chrono::duration<double>(clock::now() - wall_start_).count();
  const double done = t - t_start_;
  if (done <= 0.0 || wall <= 0.0) return -1.0;
  return (t_end_ - t) * wall / done;
}

void ProgressLine::report(long long step, double t, double dt, bool force) {
  const auto now = clock::now();
  if (!force && std::chrono::duration<double>(now - last_print_).count() < interval_) return;
  last_print_ = now;
  const double wall = std::chrono::duration<double>(now - wall_start_).count();
  const double eta = eta_seconds(t);
  log_.info("step {:>8}  t = {:.6g} s of {:.6g} s  dt = {:.3e} s  wall {:.1f} s  ETA {}", step, t, t_end_, dt, wall,
            eta < 0 ? std::string("?") : fmt::format("{:.0f} s", eta));
}

}  // namespace suite
