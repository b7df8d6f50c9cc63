#include "solvers/breach/soil/soil.hpp"

#include <cmath>

namespace suite::breach {

double grain_roughness_from_d75(double d75_mm) {
  return 0.0156 * std::pow(d75_mm, 1.0 / 6.0);
}

Soil Soil::read(const config::Section& s) {
  using config::Range;
  Soil soil;
  soil.kd = s.quantity("erodibility", "m^3/(N s)", Range::at_least(0));
  soil.tau_c = s.quantity("critical_shear_stress", "Pa", 0.0, Range::at_least(0));
  soil.s_u = s.quantity("undrained_shear_strength", "Pa", Range::at_least(0));
  soil.gamma_t = s.quantity("unit_weight", "N/m^3", Range::positive());
  if (s.has("d75")) {
    if (s.has("grain_roughness")) s.reject("d75", "give either d75 or grain_roughness, not both");
    soil.grain_roughness = grain_roughness_from_d75(s.quantity("d75", "mm", Range::positive()));
  } else {
    // 0.016: the Manning n DL Breach recommends for cohesive embankment soil (Wu 2016, report
    // v2016.4, Clarkson University); an input because it is a property of the soil.
    soil.grain_roughness = s.quantity("grain_roughness", "1", Soil::kDefaultGrainRoughness, Range::positive());
  }
  return soil;
}

}  // namespace suite::breach
