#pragma once
// The embankment soil as WinDAM C describes it (Hunt et al. 2021; Temple et al. 2005): the
// excess-stress erodibility pair (kd, tau_c) from jet-erosion tests, and the strength pair
// (s_u, gamma_t) that sets the height at which a headcut face fails. All SI.
//
// Scene form (section `soil`), US or SI units per quantity:
//   erodibility: 300 (ft/h)/psf      # kd; or 530 cm^3/(N s); 1 (ft/h)/psf = 1.7698 cm^3/(N s)
//   critical_shear_stress: 0 psf     # tau_c
//   undrained_shear_strength: 70 psf # s_u
//   unit_weight: 120 lbf/ft^3        # gamma_t (a weight: lbf, not lb)
//   grain_roughness: 0.016           # Manning n_s of the bare soil, or d75: 0.2 mm instead
#include "core/config/config.hpp"

namespace suite::breach {

struct Soil {
  // The grain roughness of a scene that gives neither it nor d75 (soil.cpp says where it comes from).
  static constexpr double kDefaultGrainRoughness = 0.016;

  double kd = 0.0;               // m^3/(N s); 1 cm^3/(N s) = 1e-6 m^3/(N s)
  double tau_c = 0.0;            // Pa
  double s_u = 0.0;              // Pa
  double gamma_t = 0.0;          // N/m^3
  double grain_roughness = 0.0;  // s/m^(1/3)

  static Soil read(const config::Section& section);
};

// Manning n of the soil grains from d75 (mm): n_s = 0.0156 d75^(1/6), the grain-roughness
// relation of the SITES / NEH 628 ch. 51 spillway erosion model (NRCS 1997; Temple et al. 1987).
double grain_roughness_from_d75(double d75_mm);

}  // namespace suite::breach
