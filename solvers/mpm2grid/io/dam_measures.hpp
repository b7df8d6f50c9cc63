#pragma once
// What a dam-breach run measures of its dam (docs/methods/mpm2grid.md, "Purpose"; issue 3, item 6).
//
// Eroded soil volume. A soil particle stands for its as-placed volume V_p^0 (mass over the
// soil's density), a lattice cell of side s around its centre. It still belongs to the dam while
// its centre lies in the dam's initial cross-section (the scene's soil regions) grown outwards by
// half a particle spacing s/2 along the axes, i.e. while its cell still overlaps the dam's
// footprint. The eroded volume is
//   V_eroded(t) = V_0 - sum of V_p^0 over the soil particles still in the grown section,
// with V_0 the initial soil volume: soil carried off the dam, wherever it went (down the
// slope, onto the run-out, out through the outlet). Elastic settling and bulging by less than
// s/2 erodes nothing; soil that slides down the face and comes to rest outside the section
// counts as eroded, soil moved from one place of the section to another does not. In m^3, m^2
// (per metre) in 2D.
//
// Crest profile. The soil surface per column of width h along x (columns [x0 + c h,
// x0 + (c + 1) h), c = 0, 1, ...; in 3D over the whole depth): the highest soil particle's y
// plus half a particle spacing (the top of its cell). Columns without soil have no entry. The
// crest height is the highest surface above the floor.
#include <vector>

#include "solvers/mpm2grid/particles/particles.hpp"
#include "solvers/mpm2grid/scenes/scene.hpp"

namespace suite::mpm2grid {

// The sum of V_p^0 over the particles whose centres lie in one of the regions grown by margin (m).
template <int Dim>
double volume_within(const Particles<Dim>& particles, const std::vector<Region>& regions, double margin);

struct ColumnTop {
  double x = 0;    // the column's centre, m
  double top = 0;  // the soil surface, m
};

// The soil surface per column of width `width` from x0, in increasing x.
template <int Dim>
std::vector<ColumnTop> crest_profile(const Particles<Dim>& soil, double x0, double width, double half_spacing);

// The highest surface of a profile minus the floor's y (NaN without soil), m.
double crest_height(const std::vector<ColumnTop>& profile, double floor);

}  // namespace suite::mpm2grid
