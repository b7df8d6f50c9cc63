#pragma once
// What a dam-breach run measures of its dam (docs/methods/mpm2grid.md, "Purpose"; issue 3, item 6).
//
// Eroded soil volume. A soil particle stands for its as-placed volume s^d (mass over the soil's
// density), the lattice cell of side s around its centre, whatever its strain. It still belongs
// to the dam while its centre lies in the dam's initial cross-section (the scene's soil regions)
// grown outwards by half a particle spacing s/2 along the axes, i.e. while its cell still
// overlaps the dam's footprint. The eroded volume is
//   V_eroded(t) = s^d (N_0 - number of soil particles still in the grown section),
// with N_0 the number at the start (counted, so that a dam that lost nothing reads exactly 0 on
// any number of ranks) and detached soil (erosion/bed_shear.hpp) never counted as in: soil
// carried off the dam, wherever it went (down the slope, onto the run-out, out through the
// outlet). Elastic settling and bulging by less than s/2 erodes nothing; soil that slides down
// the face and comes to rest outside the section counts as eroded, soil moved from one place of
// the section to another does not. In m^3, m^2 (per metre) in 2D.
//
// Crest profile. The soil surface (detached soil left out) per column of width h along x
// (columns [x0 + c h, x0 + (c + 1) h), c = 0, 1, ...; in 3D over the whole depth), read from the
// soil's fill of the column's cells (rows [y0 + r h, y0 + (r + 1) h)): the as-placed volume of
// the particles in a cell over the cell's volume (h^2 per metre in 2D, h^2 times the domain's
// depth in 3D), 1 for a cell of soil as seeded. From the column's lowest cell with soil upwards
// the surface rises by each cell's fill (at most 1) up to and including the first cell filled
// half or less, and stops there: soil as seeded reads its height to a lattice row, while grains
// strewn above the dam (a particle here and there, one-particle filaments, which fill a cell by
// 1/4 or 1/2 at two particles per cell and axis) add at most half a cell instead of lifting the
// crest to the highest grain. Columns without soil have no entry. The crest height is the
// highest surface above the floor.
#include <vector>

#include "solvers/mpm2grid/particles/particles.hpp"
#include "solvers/mpm2grid/scenes/scene.hpp"

namespace suite::mpm2grid {

// The number of particles whose centres lie in one of the regions grown by margin (m).
template <int Dim>
long long count_within(const Particles<Dim>& particles, const std::vector<Region>& regions, double margin);

struct ColumnTop {
  double x = 0;    // the column's centre, m
  double top = 0;  // the soil surface, m
};

// The soil particles in a grid of columns and rows of side h from (x0, y0): count[c * rows + r]
// (whole numbers, so that sums over ranks are exact in any order); a cell's fill is
// count * particle_fill, one particle's as-placed volume over a cell's volume.
struct SoilColumns {
  double x0 = 0, y0 = 0, h = 0;
  long columns = 0, rows = 0;
  double particle_fill = 0;
  std::vector<double> count;
};

// The counts of `soil` (particles outside the grid are left out). Over ranks: add the counts.
template <int Dim>
SoilColumns soil_columns(const Particles<Dim>& soil, double x0, double y0, double h, long columns, long rows,
                         double particle_fill);

// The soil surface per column with soil, in increasing x (the rule above).
std::vector<ColumnTop> crest_profile(const SoilColumns& cells);

// One rank's profile: the grid from x0, y0 up to its highest particle.
template <int Dim>
std::vector<ColumnTop> crest_profile(const Particles<Dim>& soil, double x0, double y0, double h, double particle_fill);

// The highest surface of a profile minus the floor's y (NaN without soil), m.
double crest_height(const std::vector<ColumnTop>& profile, double floor);

}  // namespace suite::mpm2grid
