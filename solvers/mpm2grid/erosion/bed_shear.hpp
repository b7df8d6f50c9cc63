#pragma once
// The bed-shear closure and excess-stress erosion (docs/methods/mpm2grid.md, "Bed shear and
// excess-stress erosion"). The water is inviscid, so nothing resolved carries the shear stress a
// flow puts on its bed; this closure computes it per column of the grid from the flow's depth and
// mean velocity through Manning's law, brakes the water by it, and erodes the soil at the
// excess-stress rate of jet-erosion tests.
//
// Columns. The domain is cut into columns of side h across the horizontal axes (x; x and z in 3D),
// numbered like the grid's cells. In each column:
//   bed     the bed's surface height: the highest top (y_p + s_p / 2) of the column's bed soil
//           particles (not suspended), or the floor (y_low, when it is a wall) where that is
//           higher or there is no soil; s_p = (m_p / rho_s)^(1/Dim) is a particle's as-placed
//           side. Columns without either have no bed.
//   slope   from the neighbouring columns' beds (central differences, one-sided at an edge):
//           the bed's unit normal n and secant 1 / cos(theta) = |(-dy/dx, 1, -dy/dz)|.
//   flow    the water particles above the bed (y_p > bed; the pore water lies below): their
//           volume V (V0 J) gives the depth normal to the bed d = V / (h^(Dim-1) secant), their
//           momentum over mass the mean velocity U, its part along the bed u = U - (U . n) n.
//           With the free water on its own field (coupling/free_water.hpp) the flow is the
//           column's free water instead, wherever it lies against the bed.
//           A film thinner than half a cell (d < h / 2, one particle layer at the default two
//           particles per cell) is not resolved: the column counts as dry.
//   shear   tau = rho_w g0 n_M^2 |u|^2 / d^(1/3): Manning's law (SI, wide channel: the hydraulic
//           radius is the depth) as the Darcy-Weisbach friction factor f = 8 g0 n_M^2 / d^(1/3),
//           tau = rho_w f |u|^2 / 8, with standard gravity g0: like a conductivity, a Manning n
//           is measured on Earth and keeps its friction factor under another gravity (Table
//           3.4's 3 m/s^2). In steady uniform flow down a slope S this is Manning's
//           u = (1 / n_M) d^(2/3) S^(1/2) with tau = rho_w g d S.
// Friction. After G2P every water particle above a wet column's bed loses the same velocity along
// u's direction, du = |u| dt k / (1 + dt k), k = tau / (rho_w d |u|) (1/s): the linearised law
// taken implicitly (stable at any dt; a shallow fast column cannot reverse), which removes
// tau / (1 + dt k) per unit of bed area over the column's water, spread over its depth as a
// shallow-water model does. The reaction on the bed is left out (the soil's strength, kPa,
// dwarfs the shear, tens of Pa; the erosion below is what the shear does to the soil).
// Erosion (soil `erosion: excess_stress`). Each bed soil particle carries an eroded depth e_p.
// The particles whose top lies within half their side of their column's bed form the column's
// top layer (N of them, counted over all ranks). A wet column with tau > tau_c loses the volume
// dt kd (tau - tau_c) secant h^(Dim-1) (its bed lowers vertically at the normal rate times the
// secant), shared equally by its top layer: e_p += that volume / (N s_p^(Dim-1)). On a flat bed
// seeded at two particles per cell and axis N = 2^(Dim-1) and each gains dt kd (tau - tau_c);
// on a slope, where the lattice's staircase leaves fewer particles within half a side of the
// column's top, the column still loses its volume. When e_p reaches s_p the particle is detached
// (e_p = infinity from then on, particles/particles.hpp's is_suspended): it carries no stress
// (F_E = I), moves with the water (its G2P velocity is the water grid's, a dilute suspension's
// grains) and sinks through it at the settling velocity w_s. A suspended particle whose bottom
// reaches its column's bed where tau <= tau_c (or the column is dry) deposits: e_p = 0, a bed
// particle again, stress-free; where tau > tau_c it rides on the bed (its bottom kept at the
// bed's surface) until the flow calms. With kd in m^3/(N s), tau and tau_c in Pa, the rate is in
// m/s, the units and keys of the breach model (solvers/breach/soil/soil.hpp).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mpi/comm.hpp"
#include "solvers/mpm2grid/boundary/walls.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"

namespace suite::mpm2grid {

// The water's friction on its beds. manning_n = 0: no closure.
struct BedShearSettings {
  double manning_n = 0;  // Manning n of the beds (soil surfaces and the floor), s/m^(1/3)
  bool on() const { return manning_n > 0; }
};

// The soil's excess-stress erosion (soil `erosion: excess_stress`); needs the bed shear.
struct ExcessStressSettings {
  bool on = false;
  double kd = 0;                 // erodibility, m^3/(N s)
  double tau_c = 0;              // critical shear stress, Pa
  double settling_velocity = 0;  // of detached soil in still water, m/s
};

// One column's bed and flow at the step's start.
template <int Dim>
struct BedColumn {
  bool has_bed = false;
  double bed = 0;     // the bed surface's y, m
  double secant = 1;  // 1 / cos of the bed's slope
  Vec<Dim> normal = Vec<Dim>::UnitY();
  double depth = 0;  // free water normal to the bed, m (0: dry)
  Vec<Dim> velocity = Vec<Dim>::Zero();  // u, the free water's mean velocity along the bed, m/s
  double shear = 0;                      // tau, Pa
  double top_layer = 0;                  // N, the bed particles within half their side of the bed
};

template <int Dim>
class BedShear {
 public:
  // `walls`: the domain's box and whether the floor is a wall; h the grid spacing (the columns'
  // side); the densities in kg/m^3.
  BedShear(const Walls<Dim>& walls, double h, double water_density, double soil_density, BedShearSettings shear,
           ExcessStressSettings erosion, const Vec<Dim>& gravity);

  // The columns' beds and flows from the particles as they are (the step's start). COLLECTIVE
  // over comm (nullptr: one rank): two reductions over the columns. With `free` (per water
  // particle, 1 where it is free water: the free-water field's sort, coupling/free_water.hpp) a
  // column's flow is its free water, wherever it lies against the bed; without it, the water above
  // the bed.
  void measure(const Particles<Dim>& water, const Particles<Dim>& soil, const mpi::Comm* comm,
               const std::vector<char>* free = nullptr);
  // Deposits the suspended soil particles resting on calm beds and erodes the exposed ones by dt
  // (nothing without excess-stress erosion). Right after measure(), on the same particles. Returns
  // the volume the law took over the step, m^3 (m^2 per metre in 2D): the sum over the columns with
  // a top layer under an eroding flow of dt kd (tau - tau_c) secant h^(Dim-1), the same on every
  // rank (the columns are). `detached`, where given, gets the indices of the particles this call
  // detached (their F_E set to I), in increasing order.
  double erode(Particles<Dim>& soil, double dt, std::vector<std::size_t>* detached = nullptr) const;
  // The friction on the water particles of the wet columns' flows (measure()'s `free` as there),
  // over dt.
  void brake(Particles<Dim>& water, double dt, const std::vector<char>* free = nullptr) const;
  // The soil volume the erosion has taken from particle p, m^3 (m^2 per metre in 2D): a detached
  // particle whole (s_p^Dim), another its eroded depth e_p s_p^(Dim-1); 0 once it deposits.
  double eroded_volume(const Particles<Dim>& soil, std::size_t p) const;
  // A soil particle's as-placed side s_p, m.
  double side(const Particles<Dim>& soil, std::size_t p) const;
  static bool suspended(const Particles<Dim>& soil, std::size_t p) { return is_suspended(soil.eroded[p]); }
  // Sinks a suspended particle by w_s dt along gravity, onto the bed at the most where the bed
  // erodes (where it is calm, erode() deposits it at the next step).
  void settle(Particles<Dim>& soil, std::size_t p, double dt) const;

  const std::vector<BedColumn<Dim>>& columns() const { return columns_; }
  // The column holding x (clamped to the domain's columns).
  std::size_t column_of(const Vec<Dim>& x) const;
  // The column's centre (its y: 0).
  Vec<Dim> column_centre(std::size_t c) const;
  double largest_shear() const;  // Pa, over the wet columns

 private:
  void slopes();
  bool in_top_layer(const Particles<Dim>& soil, std::size_t p) const;

  Vec<Dim> lo_;
  double h_, inv_h_, rho_w_, rho_s_;
  bool floor_;
  BedShearSettings shear_;
  ExcessStressSettings erosion_;
  Vec<Dim> down_;                  // unit vector along gravity (zero without gravity)
  std::array<long, Dim> count_{};  // columns per axis (1 along y)
  std::vector<BedColumn<Dim>> columns_;
  std::vector<double> sums_;                // per column: volume, mass, momentum (Dim), top layer
  std::vector<std::uint32_t> soil_column_;  // each soil particle's column at measure()
};

}  // namespace suite::mpm2grid
