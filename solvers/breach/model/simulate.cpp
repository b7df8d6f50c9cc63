#include "solvers/breach/model/simulate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "solvers/breach/model/dormand_prince.hpp"
#include "solvers/breach/model/peak_search.hpp"

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
    // Switches, signed so that they are positive now; one we sit on is left for this step.
    const auto g = model_.switches(t_, y_, stage_);
    for (int k = 0; k < BreachState::kSwitches; ++k)
      if (std::abs(g[static_cast<std::size_t>(k)]) > model_.switch_tolerance(k))
        e.push_back({BreachState::Event::Kind::switch_point, kStorageLessInflow,
                     g[static_cast<std::size_t>(k)] > 0 ? 1.0 : -1.0, k});
    return e;
  }
  // Shortens `s` (a trial step of size h) to end on the first event it crosses; returns the
  // step size used and sets `hit` to that event, or leaves it empty.
  double locate(Step& s, double h, std::optional<BreachState::Event>& hit);
  void apply_event(const BreachState::Event& e);
  void refresh() { model_.derivatives(t_, y_, stage_, capped_, k1_), ++result_.evaluations; }
  // Feeds the accepted step [t_, t_ + h] to the peak searches.
  void record(const Step& s, double h);
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
  PeakSearch total_peak_, breach_peak_;
  // The last accepted step, for a peak that straddles a step boundary; invalid after an event.
  struct Span {
    Step step;
    double t0 = 0.0, h = 0.0;
    Stage stage = Stage::surface_erosion;
    Flows mid, end;
    bool valid = false;
  } span_;
  double failure_storage_ = 0.0, failure_level_ = 0.0;
};

double Run::locate(Step& s, double h, std::optional<BreachState::Event>& hit) {
  hit.reset();
  const auto ev = events();
  const auto switches_at_end = model_.switches(t_ + h, s.y, stage_);  // once for all switches
  double first = h;
  for (std::size_t i = 0; i < ev.size(); ++i) {
    auto distance = [&](double dt, const StateVector& y) { return model_.distance(ev[i], t_ + dt, y, stage_); };
    const bool is_switch = ev[i].kind == BreachState::Event::Kind::switch_point;
    if ((is_switch ? ev[i].at * switches_at_end[static_cast<std::size_t>(ev[i].index)] : distance(h, s.y)) > 0.0)
      continue;
    // Illinois regula falsi on theta in (0, h]: g(0) > 0 >= g(h).
    const double tol = is_switch ? model_.switch_tolerance(ev[i].index) : 1e-12 * scale_[ev[i].component];
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
    if (!hit || b < first) first = b, hit = ev[i];
  }
  if (hit) s = step(first);
  return first;
}

void Run::apply_event(const BreachState::Event& e) {
  using Kind = BreachState::Event::Kind;
  span_.valid = false;  // a kink: no peak search across it
  if (e.kind == Kind::empty_reservoir || e.kind == Kind::switch_point) return;
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
    case Stage::internal_erosion:  // the pipe's roof collapses: the breach forms from its debris
      model_.collapse_roof(y_);
      [[fallthrough]];
    case Stage::headcut_advance:  // the headcut reaches the upstream edge of the crest
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

void Run::record(const Step& s, double h) {
  // Samples at the ends and the middle of the step; a maximum inside it, or at its start when q
  // rose through the end of the previous step (no event between), is refined on the dense output
  // (adaptive steps only: their error control keeps the interpolant close to the solution).
  const double t0 = t_, tm = t_ + 0.5 * h;
  const Flows f0 = span_.valid ? span_.end : model_.flows(t0, y_, stage_);
  const Span current{s, t0, h, stage_, model_.flows(tm, s.at(0.5), stage_), model_.flows(t0 + h, s.y, stage_), true};
  auto at = [this](const Span& sp, double t) { return model_.flows(t, sp.step.at((t - sp.t0) / sp.h), sp.stage); };
  auto track = [&](PeakSearch& peak, auto quantity) {
    const double q0 = quantity(f0), qm = quantity(current.mid), q1 = quantity(current.end);
    peak.sample(t0, q0);
    peak.sample(t0 + h, q1);
    // Without error control (fixed steps) the interpolant is not to be trusted between the ends.
    if (!sc_.time.adaptive) return;
    peak.sample(tm, qm);
    auto on = [&](const Span& sp) { return [&, sp_ptr = &sp](double t) { return quantity(at(*sp_ptr, t)); }; };
    // A search can raise the running peak only if the bracket's top sample, plus the spread of
    // its samples (a bound on what a unimodal bump adds between them), reaches it.
    auto worth = [&](double top, double low) { return top + (top - low) >= peak.value(); };
    if (qm > q0 && qm >= q1 && worth(qm, std::min(q0, q1))) peak.search(on(current), t0, t0 + h);
    if (span_.valid && q0 > qm && quantity(span_.end) > quantity(span_.mid) &&
        worth(q0, std::min(qm, quantity(span_.mid)))) {
      peak.search(on(span_), span_.t0 + 0.5 * span_.h, t0);
      peak.search(on(current), t0, tm);
    }
  };
  track(total_peak_, [](const Flows& f) { return f.total(); });
  track(breach_peak_, [](const Flows& f) { return f.breach; });
  span_ = current;
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
  // A stage that is over before it starts (a pipe already past its collapse size) ends at once.
  if (stage_ != Stage::breach_widening && model_.distance(model_.stage_end(stage_), t_, y_, stage_) <= 0.0)
    apply_event(model_.stage_end(stage_));
  refresh();
  {
    const Flows f = model_.flows(t_, y_, stage_);
    total_peak_.sample(t_, f.total());
    breach_peak_.sample(t_, f.breach);
  }
  // Stops: the hydrograph's kinks, output times (with an observer), the end. A time within
  // round-off of a stop counts as on it.
  std::vector<double> kinks;
  for (double b : sc_.inflow.breakpoints())
    if (b > ts.start && b < ts.end) kinks.push_back(b);
  std::size_t next_kink = 0;
  long output_index = 0;
  double last_emitted = -std::numeric_limits<double>::infinity();
  auto next_output = [&] { return observe_ ? ts.start + output_index * sc_.output_interval : ts.end; };
  const double eps = 1e-13 * std::max(std::abs(ts.start), std::abs(ts.end));
  double h = ts.adaptive ? std::min(ts.max_step, 1e-4 * (ts.end - ts.start)) : ts.fixed_step;
  for (;;) {
    while (next_kink < kinks.size() && kinks[next_kink] <= t_ + eps) ++next_kink;
    if (observe_ && next_output() <= t_ + eps) {
      emit();
      last_emitted = t_;
      ++output_index;
    }
    if (t_ >= ts.end - eps) break;
    const double stop = std::min({ts.end, next_kink < kinks.size() ? kinks[next_kink] : ts.end, next_output()});
    const bool to_stop = h >= stop - t_;
    const double trial = to_stop ? stop - t_ : h;
    Step s = step(trial);
    if (ts.adaptive) {
      const double err = error_norm(s, trial);
      if (!(err <= 1.0)) {
        h = trial * (std::isfinite(err) ? std::max(0.2, 0.9 * std::pow(err, -0.2)) : 0.2);
        ++result_.rejected_steps;
        if (h < 1e-12 * (ts.end - ts.start))
          throw std::runtime_error(fmt::format("breach: step size collapsed to {} s at t = {} s ({}{})", h, t_,
                                               stage_name(stage_), std::isfinite(err) ? "" : ", non-finite solution"));
        continue;
      }
      // A step cut short to reach a stop says little about the step the solution allows:
      // never let it shrink the next one.
      const double proposed = trial * std::min(5.0, std::max(0.2, 0.9 * std::pow(std::max(err, 1e-10), -0.2)));
      h = std::min(to_stop ? std::max(h, proposed) : proposed, ts.max_step);
    }
    std::optional<BreachState::Event> hit;
    const double taken = locate(s, trial, hit);
    record(s, taken);
    t_ = !hit && to_stop ? stop : t_ + taken;
    y_ = s.y;
    k1_ = s.f_end;
    ++result_.steps;
    for (double v : y_)
      if (!std::isfinite(v))
        throw std::runtime_error(
            fmt::format("breach: the solution is not finite at t = {} s ({})", t_, stage_name(stage_)));
    if (hit) {
      apply_event(*hit);
      refresh();
      const Flows f = model_.flows(t_, y_, stage_);
      total_peak_.sample(t_, f.total());
      breach_peak_.sample(t_, f.breach);
    }
    if (!ts.adaptive) h = ts.fixed_step;
  }
  if (observe_ && last_emitted != t_) emit();

  // The summary.
  Result& r = result_;
  const Flows f = model_.flows(t_, y_, stage_);
  r.peak_outflow = total_peak_.value();
  r.time_to_peak = total_peak_.time() - ts.start;
  r.peak_breach_outflow = breach_peak_.value();
  // dQ/dt at the end, along the solution: the state a second on by its final slope.
  {
    constexpr double probe = 1.0;  // s
    StateVector ahead = y_;
    for (std::size_t i = 0; i < ahead.size(); ++i) ahead[i] += probe * k1_[i];
    const double rate = (model_.flows(t_ + probe, ahead, stage_).total() - f.total()) / probe;
    r.rising_at_end = rate > 1e-9 * std::max(1.0, r.peak_outflow);
  }
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
