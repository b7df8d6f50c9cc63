#pragma once
// The water inlet on the domain's x_low side (docs/methods/mpm2grid.md, steps 4 and 6): water enters
// through the section [floor, floor + H] (over the whole depth along z in 3D) with the discharge
// q(t) per metre of width (m^2/s), either constant (the dissertation's Table 3.4: a height and a
// velocity, q = v H) or a hydrograph table with linear interpolation.
//
// Particles. The inlet emits water particles on the seeding lattice (spacing s = h /
// particles_per_cell per axis): one layer is a column of `rows` particles over the section
// (times the lattice points along z in 3D), and layers are emitted one lattice spacing apart as
// the inflow advances. The section's particle rows are those of the lattice whose centres lie
// below floor + H, so the section the particles fill is H_s = rows s (within s/2 of H); the
// velocity is v(t) = q(t) / H_s, so that the mass inflow is rho q(t) per metre whatever H is.
// The emitted length L(t) = integral of v dt = Q(t) / H_s, with Q(t) the exact integral of the
// hydrograph from 0 to t, and the layers emitted by time t are floor(L / s): the emitted mass is
// rho s H_s floor(L / s) per metre, short of rho Q(t) by less than one layer. Layer k (0, 1, ...)
// is placed where the inflowing column would have carried it, x = x_low + L - (k + 1/2) s, with
// velocity (v(t), 0[, 0]), J = 1 and the APIC matrix C = 0.
//
// Grid. The water grid's nodes on the inlet face (x <= x_low, floor <= y <= floor + H_s) get the
// inlet velocity (v(t), 0[, 0]) after the wall conditions, so that the water near the inlet moves
// at the inflow velocity rather than piling up against a wall.
//
// The inlet's state (the emitted length, layers and mass) is part of a checkpoint.
#include <vector>

#include "core/tables/hydrograph.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"

namespace suite::mpm2grid {

template <int Dim>
struct InletSettings {
  double height = 0;      // H: the section's height above the floor, m
  double spacing = 0;     // s: the particle lattice spacing, m
  double density = 1000;  // rho of the water, kg/m^3
  // The domain's box, m: x_low = lo[0], the floor lo[1], the depth along z lo[2] .. hi[2] (3D).
  Vec<Dim> lo = Vec<Dim>::Zero(), hi = Vec<Dim>::Ones();
  Hydrograph discharge = Hydrograph::constant(0);  // q(t), m^2/s (per metre of width), t in s
};

// What the inlet has emitted so far.
struct InletState {
  double length = 0;     // L at the last emission, m
  long long layers = 0;  // layers emitted
  double mass = 0;       // kg (per metre of thickness in 2D) of the particles emitted
};

template <int Dim>
class Inlet {
 public:
  // Throws std::invalid_argument if no particle row fits into the section (H < s/2) or the
  // settings are not positive; scenes check this with a message naming the key first.
  explicit Inlet(const InletSettings<Dim>& settings);

  const InletSettings<Dim>& settings() const { return s_; }
  int rows() const { return rows_; }
  double section_height() const { return rows_ * s_.spacing; }  // H_s, m
  // The velocity of the inflow at time t, q(t) / H_s, m/s.
  double velocity(double t) const;
  // The mass of one layer, kg (per metre of thickness in 2D).
  double layer_mass() const { return layer_mass_; }

  // Sets the velocity of the water grid's nodes with mass on the inlet face to the inflow's at t.
  void impose(const BlockGrid<Dim>& grid, NodeFields<Dim>& water, double t) const;
  // Adds the layers due by time t (t never decreases from one call to the next). With
  // add_particles false only the state moves on (the ranks of a decomposition but one).
  void emit(double t, Particles<Dim>& water, bool add_particles = true);

  const InletState& state() const { return state_; }
  void restore(const InletState& state) { state_ = state; }

 private:
  InletSettings<Dim> s_;
  int rows_ = 0;
  double layer_mass_ = 0;
  std::vector<Vec<Dim>> layer_;  // one layer's lattice points with x = 0
  InletState state_;
};

extern template class Inlet<2>;
extern template class Inlet<3>;

}  // namespace suite::mpm2grid
