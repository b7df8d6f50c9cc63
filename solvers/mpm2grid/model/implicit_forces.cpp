// The implicit forces (docs/methods/mpm2grid.md, "Implicit forces"; issue 29): the grid update
// of the dissertation's eq. 3.24,
//   (M + dt D) v = M v^n + dt (M g + f(x^(v))),
// with the elastic forces f of both species taken at the step's end (backward Euler). Each
// particle's trial deformation comes from the unknown node velocities v:
//   soil   F^ = (I + dt grad v_p) F^n,
//          f_i = -sum_p V_p^0 P(F^) (F^n)^T grad w_ip = -sum_p V_p^0 tau(F^) (I + dt grad v_p)^-T grad w_ip
//   water  J^ = exp(dt div v_p) J^n  (positive at any dt; the particle update takes the same),
//          f_i = sum_p V_p^0 J^ p(J^) grad w_ip
// (eqs. 3.16, 3.17: the derivatives of the elastic energies at the moved nodes x^ = x + dt v, so
// the update is the stationary point of a potential, convex for the water). The soil's stress is
// that of its trial state returned onto Drucker-Prager (with the saturation of the step's start;
// the particle update returns it again with the step's own); with plastic_solve false it is the
// elastic trial state's and the projection follows the solve, as the dissertation's eq. 3.26 has
// it, which kept example 2's dam from eroding (docs/mpm2grid.md, "Implicit forces"). The water's
// tension clamp (materials/weakly_compressible_water.hpp) is an
// active set: each particle's side of it from the step's start, fixed during the solve (its kink
// inside the solve stalled Newton), with clamp_passes > 1 solved again until the sides settle.
// The buoyancy stays the step's start's (the node pressures of P2G).
//
// The unknowns are the velocities of both species on this rank's owned nodes with mass. With G(v)
// the lumped drag update of coupling/drag_solve.hpp with the forces f(v), and W the walls' and
// the inlet's conditions (applied after every update), the solve finds the fixed point
//   R(v) = v - W(G(v)) = 0
// by matrix-free Newton-Krylov (core/petsc/newton_krylov.hpp). W(G(0)) is the explicit update: the
// first guess. R is in m/s; its Jacobian I + dt^2 (M + dt D)^-1 K (K the stiffness) has the drag's
// node-local block inverted in G, so GMRES needs no preconditioner for the drag, but its
// iterations grow with the cells a wave crosses in a step (docs/mpm2grid.md, "Implicit forces").
// A trial velocity that inverts a soil particle (det(I + dt grad v) <= 0) or under- or overflows
// a water particle's exp(dt div v) J lies outside R's domain: the line search shortens its step.
// Every residual evaluation is COLLECTIVE (the halo copy of the trial velocities, the halo sum of
// the forces, one reduction).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "solvers/mpm2grid/kernels/vector_clones.hpp"
#include "solvers/mpm2grid/materials/drucker_prager_return.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"
#include "solvers/mpm2grid/model/trial_deformation.hpp"

namespace suite::mpm2grid {

namespace {

// A mass-free copy of a species' particles at their positions (for G2P of trial velocities and a
// P2G of stresses alone): volume0 kept, J = 1 (the stresses given are Kirchhoff's), no mass,
// velocity or C.
template <int Dim>
void make_probe(const Particles<Dim>& P, Particles<Dim>& probe) {
  probe.x = P.x;
  probe.volume0 = P.volume0;
  probe.J.assign(P.size(), 1.0);
  probe.mass.assign(P.size(), 0.0);
  probe.v.assign(P.size(), Vec<Dim>::Zero());
  probe.C.assign(P.size(), Mat<Dim>::Zero());
}

}  // namespace

template <int Dim>
void Simulation<Dim>::solve_grid_implicit(double dt) {
  ImplicitState<Dim>& s = implicit_;
  const double t_next = time_ + dt;
  s.soil_slots.clear();
  s.water_slots.clear();
  const std::vector<char>* owned = dd_ ? &dd_->owned_blocks() : nullptr;
  for (std::size_t i = 0; i < grid_.nodes(); ++i) {
    if (owned && !(*owned)[i / BlockGrid<Dim>::kNodes]) continue;
    if (soil_nodes_.mass[i] > 0) s.soil_slots.push_back(static_cast<long>(i));
    if (water_nodes_.mass[i] > 0) s.water_slots.push_back(static_cast<long>(i));
  }
  s.soil_base = soil_nodes_.force;
  s.water_base = water_nodes_.force;
  make_probe(soil_, s.soil_probe);
  // The grains the excess-stress erosion detached: stress-free through the step, as the particle
  // update leaves them (F = I).
  s.stress_free.assign(soil_.size(), 0);
  if (s_.erosion.on)
    for (std::size_t p = 0; p < soil_.size(); ++p) s.stress_free[p] = bed_shear_->suspended(soil_, p);
  make_probe(water_, s.water_probe);
  // The stresses' node sums: sized once a step; each evaluation zeroes the forces alone (the
  // probes' mass, momentum and pressure sums are zero, and nothing reads them).
  s.water_force.reset(grid_.nodes());
  s.soil_force.reset(grid_.nodes());
  const std::size_t n = Dim * (s.soil_slots.size() + s.water_slots.size());
  std::vector<double> x(n, 0.0), r(n);
  // The tension clamp's active set from the step's start; then, with clamp_passes > 1, more
  // Newton solves, each from the last one's solution, until no particle's side of the clamp
  // changes or clamp_passes solves are done.
  const WeaklyCompressibleWater& eos = s_.water.eos;
  const auto held = [&](double J) { return eos.unclamped_pressure(J) < eos.min_pressure; };
  s.water_held.resize(water_.size());
  for (std::size_t p = 0; p < water_.size(); ++p) s.water_held[p] = held(water_.J[p]);
  // The first guess: the explicit update W(G(0)); where that lies outside R's domain (a long
  // step's explicit forces overshoot) and the solve cannot even start, zero.
  implicit_residual(x.data(), r.data(), dt, t_next);
  for (std::size_t k = 0; k < n; ++k) x[k] = -r[k];
  s.evaluations_total += 1;
  const auto solve = [&] {
    for (bool from_zero = false;; from_zero = true) {
      s.last = newton_->solve(x, [&](const double* v, double* out) { return implicit_residual(v, out, dt, t_next); });
      s.evaluations_total += s.last.residual_evaluations;
      const bool could_not_start =
          !s.last.converged && s.last.newton_iterations == 0 && s.last.reason == "DIVERGED_FUNCTION_DOMAIN";
      if (from_zero || !could_not_start) return;
      x.assign(n, 0.0);
    }
  };
  double changed = 0;
  for (s.passes = 1;; ++s.passes) {
    solve();
    if (!s.last.converged)
      throw ImplicitSolveFailed(fmt::format(
          "the implicit forces' Newton-Krylov solve did not converge at step {} (t = {:.6g} s, dt = {:.4g} s): {} "
          "after {} Newton and {} GMRES iterations",
          steps_, time_, dt, s.last.reason, s.last.newton_iterations, s.last.krylov_iterations));
    s.newton_total += s.last.newton_iterations;
    s.krylov_total += s.last.krylov_iterations;
    s.newton_most = std::max(s.newton_most, s.last.newton_iterations);
    s.krylov_most = std::max(s.krylov_most, s.last.krylov_iterations);
    if (s_.clamp_passes == 1) break;
    implicit_residual(x.data(), r.data(), dt, t_next);  // J^ at the solution
    s.evaluations_total += 1;
    changed = 0;
    for (std::size_t p = 0; p < water_.size(); ++p) {
      const bool now = held(s.water_trial_J[p]);
      changed += now != static_cast<bool>(s.water_held[p]);
      s.water_held[p] = now;
    }
    changed = sum_over_ranks(changed);
    if (changed == 0 || s.passes >= s_.clamp_passes) break;
  }
  s.passes_total += s.passes;
  s.clamp_changed_steps += changed > 0;
  // The solution's velocities (the walls and the inlet act on them next, as after any update).
  set_unknown_velocities(x.data());
}

// Calls f(velocity component, k) for the unknowns' node velocity components in the order of the
// unknowns (soil slots, then water slots, Dim components each).
template <int Dim>
template <class F>
void Simulation<Dim>::for_each_unknown(F&& f) {
  std::size_t k = 0;
  for (auto [slots, nodes] :
       {std::pair{&implicit_.soil_slots, &soil_nodes_}, std::pair{&implicit_.water_slots, &water_nodes_}})
    for (const long i : *slots)
      for (int d = 0; d < Dim; ++d) f(nodes->velocity[static_cast<std::size_t>(i)][d], k++);
}

// Both species' node velocities: the unknowns x on their slots, zero elsewhere.
template <int Dim>
void Simulation<Dim>::set_unknown_velocities(const double* x) {
  for (auto* f : {&soil_nodes_, &water_nodes_}) std::fill(f->velocity.begin(), f->velocity.end(), Vec<Dim>::Zero());
  for_each_unknown([&](double& v, std::size_t k) { v = x[k]; });
}

// The walls' and the inlet's conditions on the node velocities (W).
template <int Dim>
void Simulation<Dim>::constrain(double t_next) {
  water_walls_.apply(grid_, water_nodes_);
  s_.walls.apply(grid_, soil_nodes_);
  if (inlet_) inlet_->impose(grid_, water_nodes_, t_next);
}

// r = v - W(G(v)) for the unknowns x (module comment); leaves W(G(v)) in the node velocities.
// False (on every rank) where the trial velocities lie outside R's domain (trial_forces).
template <int Dim>
bool Simulation<Dim>::implicit_residual(const double* x, double* r, double dt, double t_next) {
  set_unknown_velocities(x);
  const bool valid = trial_forces(dt);
  solve_grid_velocities(soil_nodes_, water_nodes_, dt, DragScheme::lumped);
  constrain(t_next);
  for_each_unknown([&](double& v, std::size_t k) { r[k] = x[k] - v; });
  return valid;
}

// The node forces f(v) of the velocities in the node fields (on this rank's owned slots), added
// to the fixed ones in the fields' force sums. False (on every rank) where the trial velocities
// lie outside R's domain (module comment).
template <int Dim>
SUITE_VECTOR_CLONES bool Simulation<Dim>::trial_forces(double dt) {
  ImplicitState<Dim>& s = implicit_;
  if (dd_) dd_->copy_to_ghosts(soil_nodes_, water_nodes_);
  s.water_pressure.resize(water_.size());
  s.water_trial_J.resize(water_.size());
  const WeaklyCompressibleWater& eos = s_.water.eos;
  // Particles the trial velocities take outside R's domain: soil with det(I + dt grad v) <= 0,
  // water whose J^ p(J^) is no number.
  double outside = 0;
  grid_to_particles_each<VelocityGradient::divergence>(
      s.water_probe, grid_, water_nodes_, nullptr, nullptr, &water_fold_, [&](std::size_t p, double div) {
        const double trial = std::exp(dt * div) * water_.J[p];
        s.water_trial_J[p] = trial;
        // The Kirchhoff pressure J^ p(J^): P2G multiplies by the probe's J, 1.
        // (Held at a zero clamp: no stress, however far a splash's particle has spread.)
        s.water_pressure[p] = s.water_held[p] ? (eos.min_pressure == 0 ? 0.0 : trial * eos.min_pressure)
                                              : trial * eos.unclamped_pressure(trial);
        // exp(dt div v) under- or overflowed (a wild first guess: 0 * p(0) is NaN).
        if (!std::isfinite(s.water_pressure[p])) ++outside, s.water_pressure[p] = 0;
      });
  s.soil_trial.resize(soil_.size());
  s.soil_stress.resize(soil_.size());
  grid_to_particles_each<VelocityGradient::full>(s.soil_probe, grid_, soil_nodes_, nullptr, nullptr, &fold_,
                                                 [&](std::size_t p, const Mat<Dim>& grad_v) {
                                                   s.soil_trial[p] = trial_deformation(grad_v, soil_.F[p], dt);
                                                   const Mat<Dim> step = Mat<Dim>::Identity() + dt * grad_v;
                                                   // A detached grain (excess-stress erosion) carries no
                                                   // stress: its deformation does not matter.
                                                   if (s.stress_free[p]) {
                                                     s.soil_stress[p] = Mat<Dim>::Zero();
                                                     return;
                                                   }
                                                   outside += !(step.determinant() > 0);
                                                   s.soil_stress[p] = step.inverse().transpose();
                                                 });
  trial_stresses(dt);
  for (auto* f : {&s.water_force, &s.soil_force}) std::fill(f->force.begin(), f->force.end(), Vec<Dim>::Zero());
  spread(s.water_probe, water_schedule_, {.pressure = &s.water_pressure, .walls = &water_fold_}, s.water_force);
  spread(s.soil_probe, soil_schedule_, {.tau = &s.soil_stress, .walls = &fold_}, s.soil_force);
  if (dd_) {
    dd_->sum_forces_to_owners(s.water_force);
    dd_->sum_forces_to_owners(s.soil_force);
  }
  for (std::size_t i = 0; i < grid_.nodes(); ++i) {
    water_nodes_.force[i] = s.water_base[i] + s.water_force.force[i];
    soil_nodes_.force[i] = s.soil_base[i] + s.soil_force.force[i];
  }
  return max_over_ranks(outside) == 0;
}

// The soil's stresses tau(F^) (I + dt grad v)^-T from the trial F^ in soil_trial and the
// (I + dt grad v)^-T in soil_stress; with plastic_solve, tau of F^ returned onto Drucker-Prager,
// kBatch particles at a time as in the particle update (HenckyDruckerPrager::project_all).
template <int Dim>
SUITE_INLINE_CALLS void Simulation<Dim>::trial_stresses(double dt) {
  ImplicitState<Dim>& s = implicit_;
  const HenckyDruckerPrager& material = s_.soil.material;
  if (!s_.plastic_solve) {
    for (std::size_t p = 0; p < soil_.size(); ++p)
      if (!s.stress_free[p]) s.soil_stress[p] = material.template kirchhoff<Dim>(s.soil_trial[p]) * s.soil_stress[p];
    return;
  }
  constexpr int kBatch = 4;
  for (std::size_t first = 0; first < soil_.size(); first += kBatch) {
    const int count = static_cast<int>(std::min<std::size_t>(kBatch, soil_.size() - first));
    Mat<Dim> trial[kBatch];
    double log_jp[kBatch], saturation[kBatch];
    for (int k = 0; k < kBatch; ++k) {  // the last batch filled up with F = I
      const std::size_t p = first + static_cast<std::size_t>(k);
      const bool real = k < count;
      trial[k] = real ? s.soil_trial[p] : Mat<Dim>::Identity();
      log_jp[k] = real ? soil_.log_jp[p] : 0.0;
      // With the excess-stress erosion the cohesion does not fall with the saturation (as in the
      // particle update).
      saturation[k] = real && !s_.erosion.on ? soil_.saturation[p] : 0.0;
    }
    ReturnResult<Dim> r[kBatch];
    material.template project_all<Dim, kBatch>(trial, log_jp, saturation, r, dt);
    for (int k = 0; k < count; ++k) {
      const std::size_t p = first + static_cast<std::size_t>(k);
      if (s.stress_free[p]) continue;  // zero already
      const Mat<Dim> tau = r[k].has_stress ? r[k].stress : material.template kirchhoff<Dim>(r[k].F);
      s.soil_stress[p] = tau * s.soil_stress[p];
    }
  }
}

template void Simulation<2>::solve_grid_implicit(double);
template void Simulation<3>::solve_grid_implicit(double);

}  // namespace suite::mpm2grid
