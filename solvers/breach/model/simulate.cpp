#include "solvers/breach/model/simulate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "solvers/breach/model/dormand_prince.hpp"

namespace suite::breach {

const char* stage_name(Stage stage) {
  switch (stage) {
    case Stage::internal_erosion:
      return "internal erosion";
    case Stage::surface_erosion:
      return "surface erosion";
    case Stage::headcut_advance:
      return "headcut advance";
    case Stage::breach_formation:
      return "breach formation";
    case Stage::breach_widening:
      return "breach widening";
  }
  return "?";
}

namespace {

// The maximum of a sampled curve, refined by the parabola through the three samples around a
// sampled maximum (third-order accurate in the spacing, so the peak does not depend on where
// the steps happen to fall).
class PeakTracker {
 public:
  void add(double t, double q) {
    if (q > value_) value_ = q, time_ = t;
    t_[0] = t_[1], t_[1] = t_[2], t_[2] = t;
    q_[0] = q_[1], q_[1] = q_[2], q_[2] = q;
    if (++count_ < 3 || !(q_[1] >= q_[0] && q_[1] > q_[2])) return;
    const double d0 = (q_[1] - q_[0]) / (t_[1] - t_[0]), d1 = (q_[2] - q_[1]) / (t_[2] - t_[1]);
    const double curvature = (d1 - d0) / (t_[2] - t_[0]);  // half the second derivative
    if (!(curvature < 0.0)) return;
    const double tv = 0.5 * (t_[0] + t_[1]) - d0 / (2.0 * curvature);
    if (tv < t_[0] || tv > t_[2]) return;
    const double qv = q_[1] + (tv - t_[1]) * (d0 + curvature * (tv - t_[0]));
    // Accept only a refinement of the order of the sampled variation (no overshoot at kinks).
    if (qv > value_ && qv <= q_[1] + (q_[1] - std::min(q_[0], q_[2]))) value_ = qv, time_ = tv;
  }
  // After a kink (an event): the next parabola must not span it.
  void restart() { count_ = 0; }
  double value() const { return value_; }
  double time() const { return time_; }

 private:
  double t_[3] = {0, 0, 0}, q_[3] = {0, 0, 0};
  int count_ = 0;
  double value_ = -1.0, time_ = 0.0;
};

class Run {
 public:
  Run(const Scene& scene, const Observer& observe)
      : sc_(scene), model_(scene), observe_(observe), scale_(model_.scales()) {}

  Result run();

 private:
  using Step = DormandPrinceStep<kComponents>;
  Step step(double h) {
    auto f = [&](double t, const StateVector& y, StateVector& dy) {
      ++result_.evaluations;
      model_.derivatives(t, y, stage_, capped_, dy);
    };
    return dormand_prince_step<kComponents>(f, t_, y_, k1_, h);
  }
  double error_norm(const Step& s, double h) const {
    double sum = 0.0;
    for (std::size_t i = 0; i < kComponents; ++i) {
      // The storage's error is W's error, but its size is the storage's, not W's (W carries the
      // whole inflow volume so far, which would loosen the control as the storm goes on).
      const double size = i == kStorageLessInflow
                              ? std::max(std::abs(model_.storage(t_, y_)), std::abs(model_.storage(t_ + h, s.y)))
                              : std::max(std::abs(y_[i]), std::abs(s.y[i]));
      const double tol = sc_.time.tolerance * (size + scale_[i]);
      sum += (s.error[i] / tol) * (s.error[i] / tol);
    }
    return std::sqrt(sum / static_cast<double>(kComponents));
  }
  // The events that can end the current step, first the stage's own.
  std::vector<BreachState::Event> events() const {
    std::vector<BreachState::Event> e;
    if (stage_ != Stage::breach_widening) e.push_back(model_.stage_end(stage_));
    if (stage_ >= Stage::breach_formation && !capped_) e.push_back(model_.width_cap());
    // A reservoir drained to the foundation empties in finite time (Q ~ V^0.75 for a power-law
    // basin): the step must end there, not carry the storage below zero.
    if (model_.storage(t_, y_) > 0.0) e.push_back(model_.empty_reservoir());
    return e;
  }
  // Shortens `s` (a trial step of size h) to end on the first event it crosses; returns the
  // step size used and sets `hit` to that event, or leaves it empty.
  double locate(Step& s, double h, std::optional<BreachState::Event>& hit);
  void apply_event(const BreachState::Event& e);
  void refresh() { model_.derivatives(t_, y_, stage_, capped_, k1_), ++result_.evaluations; }
  void record();
  void emit();

  const Scene& sc_;
  BreachState model_;
  const Observer& observe_;
  StateVector scale_;
  double t_ = 0.0;
  StateVector y_{}, k1_{};
  Stage stage_ = Stage::surface_erosion;
  bool capped_ = false;
  Result result_;
  PeakTracker total_peak_, breach_peak_;
  double failure_storage_ = 0.0, failure_level_ = 0.0;
};

double Run::locate(Step& s, double h, std::optional<BreachState::Event>& hit) {
  hit.reset();
  const auto ev = events();
  double first = h;
  for (std::size_t i = 0; i < ev.size(); ++i) {
    auto distance = [&](double dt, const StateVector& y) { return model_.distance(ev[i], t_ + dt, y); };
    if (distance(h, s.y) > 0.0) continue;
    // Illinois regula falsi on theta in (0, h]: g(0) > 0 >= g(h).
    const double tol = 1e-12 * scale_[ev[i].component];
    // ga, gb are the (Illinois-halved) end values that set the secant; fb is g(b) itself.
    double a = 0.0, ga = distance(0.0, y_), b = h, gb = distance(h, s.y), fb = gb;
    int side = 0;
    for (int it = 0; it < 200 && fb < -tol && b - a > 1e-15 * h; ++it) {
      const double theta = std::clamp((a * gb - b * ga) / (gb - ga), a + 1e-3 * (b - a), b - 1e-3 * (b - a));
      const double g = distance(theta, step(theta).y);
      if (g > 0.0) {
        a = theta, ga = g;
        if (side == -1) gb *= 0.5;
        side = -1;
      } else {
        b = theta, gb = fb = g;
        if (side == 1) ga *= 0.5;
        side = 1;
      }
    }
    if (b < first) first = b, hit = ev[i];
  }
  if (hit) s = step(first);
  return first;
}

void Run::apply_event(const BreachState::Event& e) {
  using Kind = BreachState::Event::Kind;
  total_peak_.restart();
  breach_peak_.restart();
  if (e.kind == Kind::empty_reservoir) return;
  y_[e.component] = e.at;
  if (e.kind == Kind::width_cap) {
    capped_ = true;
    return;
  }
  switch (stage_) {
    case Stage::surface_erosion:
      stage_ = Stage::headcut_advance;
      result_.headcut_formation_time = t_ - sc_.time.start;
      break;
    case Stage::internal_erosion:  // the pipe's roof collapses: the breach forms from its invert
    case Stage::headcut_advance:   // the headcut reaches the upstream edge of the crest
      stage_ = Stage::breach_formation;
      result_.initiation_time = t_ - sc_.time.start;
      capped_ = y_[kBottomWidth] >= sc_.dam.crest_length;
      failure_storage_ = model_.flows(t_, y_, stage_).storage;
      failure_level_ = model_.flows(t_, y_, stage_).level;
      break;
    case Stage::breach_formation:
      stage_ = Stage::breach_widening;
      result_.foundation_time = t_ - sc_.time.start;
      break;
    case Stage::breach_widening:
      break;
  }
}

void Run::record() {
  const Flows f = model_.flows(t_, y_, stage_);
  total_peak_.add(t_, f.total());
  breach_peak_.add(t_, f.breach);
}

void Run::emit() {
  if (!observe_) return;
  Sample s;
  s.time = t_;
  s.stage = stage_;
  s.flows = model_.flows(t_, y_, stage_);
  s.stress = model_.stress(s.flows, y_, stage_);
  s.face_erosion = y_[kFaceErosion];
  s.headcut_position = y_[kHeadcutPosition];
  s.headcut_height = stage_ >= Stage::headcut_advance ? model_.headcut_height(y_) : 0.0;
  s.invert = model_.invert(y_, stage_);
  s.bottom_width = y_[kBottomWidth];
  s.top_width = model_.top_width(y_, stage_);
  s.eroded_volume = model_.eroded_volume(y_, stage_);
  observe_(s);
}

Result Run::run() {
  const TimeSettings& ts = sc_.time;
  t_ = ts.start;
  y_ = model_.initial();
  stage_ = model_.first_stage();
  const double storage0 = y_[kStorageLessInflow];
  refresh();
  record();
  emit();
  // Stops: the hydrograph's kinks, output times (with an observer), the end.
  std::vector<double> kinks;
  for (double b : sc_.inflow.breakpoints())
    if (b > ts.start && b < ts.end) kinks.push_back(b);
  std::size_t next_kink = 0;
  long output_index = 1;
  auto next_output = [&] { return observe_ ? ts.start + output_index * sc_.output_interval : ts.end; };
  double h = ts.adaptive ? std::min(ts.max_step, 1e-4 * (ts.end - ts.start)) : ts.fixed_step;
  while (t_ < ts.end) {
    const double stop = std::min({ts.end, next_kink < kinks.size() ? kinks[next_kink] : ts.end, next_output()});
    const bool to_stop = h >= stop - t_;
    const double trial = to_stop ? stop - t_ : h;
    Step s = step(trial);
    if (ts.adaptive) {
      const double err = error_norm(s, trial);
      if (!(err <= 1.0)) {
        if (!std::isfinite(err) && trial < 1e-12 * (ts.end - ts.start))
          throw std::runtime_error(fmt::format("breach: the solution is not finite at t = {} s ({}), step {} s", t_,
                                               stage_name(stage_), trial));
        h = trial * (std::isfinite(err) ? std::max(0.2, 0.9 * std::pow(err, -0.2)) : 0.2);
        ++result_.rejected_steps;
        if (h < 1e-12 * (ts.end - ts.start))
          throw std::runtime_error(
              fmt::format("breach: step size collapsed to {} s at t = {} s ({})", h, t_, stage_name(stage_)));
        continue;
      }
      h = trial * std::min(5.0, std::max(0.2, 0.9 * std::pow(std::max(err, 1e-10), -0.2)));
      h = std::min(h, ts.max_step);
    }
    std::optional<BreachState::Event> hit;
    const double taken = locate(s, trial, hit);
    const bool landed = !hit && to_stop;
    t_ = landed ? stop : t_ + taken;
    y_ = s.y;
    k1_ = s.f_end;
    ++result_.steps;
    for (double v : y_)
      if (!std::isfinite(v))
        throw std::runtime_error(
            fmt::format("breach: the solution is not finite at t = {} s ({})", t_, stage_name(stage_)));
    if (hit) {
      record();  // the state reaching the event, then the state after it: Q may have a kink here
      apply_event(*hit);
      refresh();
    }
    record();
    if (landed) {
      if (next_kink < kinks.size() && stop == kinks[next_kink]) ++next_kink, refresh();
      if (observe_ && stop == next_output()) {
        emit();
        ++output_index;
      }
    }
    if (!ts.adaptive) h = ts.fixed_step;
  }

  // The summary.
  Result& r = result_;
  const Flows f = model_.flows(t_, y_, stage_);
  r.peak_outflow = total_peak_.value();
  r.time_to_peak = total_peak_.time() - ts.start;
  r.peak_breach_outflow = breach_peak_.value();
  r.final_stage = stage_;
  r.final_level = f.level;
  r.final_invert = model_.invert(y_, stage_);
  r.final_depth = sc_.dam.crest() - r.final_invert;
  r.final_bottom_width = y_[kBottomWidth];
  r.final_top_width = model_.top_width(y_, stage_);
  r.eroded_volume = model_.eroded_volume(y_, stage_);
  if (r.failed()) {
    r.volume_above_invert_at_failure = failure_storage_ - sc_.reservoir.storage.volume(r.final_invert);
    r.head_above_invert_at_failure = failure_level_ - r.final_invert;
  }
  r.inflow_volume = sc_.inflow.volume(ts.start, t_);
  r.outflow_volume = y_[kBreachVolume] + y_[kCrestVolume] + y_[kSpillwayVolume];
  r.storage_change = f.storage - storage0;
  r.mass_balance_error = r.inflow_volume - r.outflow_volume - r.storage_change;
  return r;
}

}  // namespace

Result simulate(const Scene& scene, const Observer& observe) {
  return Run(scene, observe).run();
}

}  // namespace suite::breach
