#include "solvers/mpm2grid/boundary/inlet.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace suite::mpm2grid {

template <int Dim>
Inlet<Dim>::Inlet(const InletSettings<Dim>& settings) : s_(settings) {
  if (!(s_.spacing > 0) || !(s_.height > 0) || !(s_.density > 0))
    throw std::invalid_argument("an inlet needs a positive height, particle spacing and density");
  // The lattice rows whose centres floor + (j + 1/2) s lie below floor + H.
  rows_ = static_cast<int>(std::llround(s_.height / s_.spacing));
  if (rows_ < 1) throw std::invalid_argument("an inlet lower than half a particle spacing holds no particle row");
  // One layer: rows along y, and the lattice points of the domain's depth along the other axes.
  long long across = 1;
  Index<Dim> count;
  count[0] = 1;
  count[1] = rows_;
  for (int d = 2; d < Dim; ++d) count[d] = static_cast<int>(std::llround((s_.hi[d] - s_.lo[d]) / s_.spacing));
  for (int d = 1; d < Dim; ++d) across *= count[d];
  for (long long n = 0; n < across; ++n) {
    long long r = n;
    Vec<Dim> x = Vec<Dim>::Zero();
    for (int d = 1; d < Dim; ++d) {
      x[d] = s_.lo[d] + (static_cast<double>(r % count[d]) + 0.5) * s_.spacing;
      r /= count[d];
    }
    layer_.push_back(x);
  }
  layer_mass_ = static_cast<double>(layer_.size()) * s_.density * std::pow(s_.spacing, Dim);
}

template <int Dim>
double Inlet<Dim>::velocity(double t) const {
  return s_.discharge(t) / section_height();
}

template <int Dim>
void Inlet<Dim>::impose(const BlockGrid<Dim>& grid, NodeFields<Dim>& water, double t) const {
  const double tol = 1e-9 * grid.spacing(), top = s_.lo[1] + section_height();
  Vec<Dim> v = Vec<Dim>::Zero();
  v[0] = velocity(t);
  for (long i = 0; i < static_cast<long>(water.mass.size()); ++i) {
    if (!(water.mass[i] > 0)) continue;
    const Vec<Dim> x = grid.position(i);
    if (x[0] <= s_.lo[0] + tol && x[1] >= s_.lo[1] - tol && x[1] <= top + tol) water.velocity[i] = v;
  }
}

template <int Dim>
void Inlet<Dim>::emit(double t, Particles<Dim>& water, bool add_particles) {
  const double s = s_.spacing, length = s_.discharge.cumulative(t) / section_height();
  const auto due = static_cast<long long>(std::floor(length / s));
  Vec<Dim> v = Vec<Dim>::Zero();
  v[0] = velocity(t);
  const double volume = std::pow(s, Dim), mass = s_.density * volume;
  for (long long k = state_.layers; k < due; ++k) {
    const double x = s_.lo[0] + length - (static_cast<double>(k) + 0.5) * s;
    for (Vec<Dim> p : layer_) {
      p[0] = x;
      if (add_particles) water.add(p, v, mass, volume);
      state_.mass += mass;
    }
  }
  state_.layers = std::max(state_.layers, due);
  state_.length = length;
}

template class Inlet<2>;
template class Inlet<3>;

}  // namespace suite::mpm2grid
