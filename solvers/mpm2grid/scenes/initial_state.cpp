#include "solvers/mpm2grid/scenes/initial_state.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solvers/mpm2grid/materials/drucker_prager_return.hpp"

namespace suite::mpm2grid {

template <int Dim>
InitialState<Dim>::InitialState(const Scene<Dim>& scene, double spacing)
    : scene_(scene), spacing_(spacing), top_(-std::numeric_limits<double>::infinity()) {
  for (const auto* regions : {&scene.water_regions, &scene.soil_regions})
    for (const auto& r : *regions) top_ = std::max(top_, r.kind == Region::Kind::box ? r.hi[1] : r.floor + r.height);
  k0_ = scene.initial.k0.value_or(1 - scene.simulation.soil.material.sin_friction);
  g_ = std::abs(scene.simulation.gravity[1]);
}

template <int Dim>
InitialPoint InitialState<Dim>::at(const Vec<Dim>& x, const Seeded& here) const {
  const auto& s = scene_.simulation;
  InitialPoint out;
  const bool water = here.water && (scene_.hydrostatic_surface || scene_.initial.hydrostatic);
  const bool soil = here.soil && scene_.initial.geostatic;
  if (!(water || soil) || !(g_ > 0)) return out;
  // The unit weight the skeleton carries of a soil point (Pa/m): its dry weight, less the
  // buoyancy where it has pore water.
  const double buoyed = s.buoyancy ? (1 - s.soil.porosity) * s.water.density : 0.0;
  const auto effective_weight = [&](const Seeded& at) {
    return at.soil ? (s.soil.density - (at.water ? buoyed : 0.0)) * g_ : 0.0;
  };
  double sigma = 0.5 * spacing_ * effective_weight(here);
  double surface = x[1] + 0.5 * spacing_;  // the top face of the water run so far
  bool in_run = here.water;
  Vec<Dim> above = x;
  for (long k = 1;; ++k) {
    above[1] = x[1] + static_cast<double>(k) * spacing_;
    if (!(above[1] < top_)) break;
    const Seeded at = seeded_at(scene_, above);
    if (in_run) {
      if (at.water) {
        surface = above[1] + 0.5 * spacing_;
      } else {
        in_run = false;
      }
    }
    if (!soil && !in_run) break;
    sigma += spacing_ * effective_weight(at);
  }
  if (water)
    out.pressure = scene_.hydrostatic_surface ? s.water.density * g_ * std::max(0.0, *scene_.hydrostatic_surface - x[1])
                                              : s.water.density * g_ * (surface - x[1]);
  if (soil) out.vertical_effective = sigma;
  return out;
}

template <int Dim>
double InitialState<Dim>::water_j(double pressure) const {
  const auto& eos = scene_.simulation.water.eos;
  return pressure > 0 ? std::pow(1 + pressure / eos.bulk_modulus, -1 / eos.gamma) : 1.0;
}

template <int Dim>
Mat<Dim> InitialState<Dim>::soil_gradient(double vertical_effective, double saturation) const {
  const auto& m = scene_.simulation.soil.material;
  if (!(vertical_effective > 0)) return Mat<Dim>::Identity();
  // The Cauchy stress (tension positive) asked for; tau = J sigma with J = exp(tr eps) from the
  // strain itself, found by a few fixed-point passes (J - 1 is of the order of the strain).
  Vector<Dim> sigma = Vector<Dim>::Constant(-k0_ * vertical_effective);
  sigma[1] = -vertical_effective;
  Vector<Dim> eps = Vector<Dim>::Zero();
  for (int pass = 0; pass < 4; ++pass) {
    const Vector<Dim> tau = std::exp(eps.sum()) * sigma;
    // tau = 2 mu eps + lambda tr(eps) 1  =>  tr eps = tr tau / (2 mu + Dim lambda).
    const double trace = tau.sum() / (2 * m.mu + Dim * m.lambda);
    eps = (tau - Vector<Dim>::Constant(m.lambda * trace)) / (2 * m.mu);
  }
  eps = m.template return_strain<Dim>(eps, saturation).eps;
  return eps.array().exp().matrix().asDiagonal();
}

template class InitialState<2>;
template class InitialState<3>;

}  // namespace suite::mpm2grid
