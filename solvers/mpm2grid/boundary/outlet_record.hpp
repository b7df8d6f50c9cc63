#pragma once
// The outflow hydrograph Q(t) at the open sides (docs/methods/mpm2grid.md, step 6): particles that leave
// through an open side are removed and their masses booked (Simulation::outflow()); sampled at
// the series times, the mass booked since the previous sample over the interval's length and
// the species' density gives the mean discharge over that interval:
//   Q_w = (M_w(t) - M_w(t_prev)) / (rho_w (t - t_prev)),   Q_s likewise with rho_s,
// in m^3/s, or m^2/s (per metre of width) in 2D. Soil volumes are as-placed volumes (mass over
// the soil's density). The record keeps the peak of Q_w and the time it was sampled at (the end
// of its interval). Its state is part of a checkpoint.

namespace suite::mpm2grid {

struct Discharges {
  double water = 0, soil = 0;  // m^3/s (m^2/s in 2D)
};

struct OutletRecord {
  double last_time = 0;                            // s, the previous sample
  double last_water_mass = 0, last_soil_mass = 0;  // kg booked as outflow by then
  double peak_water_discharge = 0, peak_time = 0;  // m^3/s (m^2/s in 2D), s

  // The mean discharges since the previous sample; moves the sample on to t. The first sample
  // (t = last_time, at the start) gives zero.
  Discharges sample(double t, double water_mass_out, double soil_mass_out, double water_density, double soil_density) {
    Discharges q;
    if (t > last_time) {
      const double dt = t - last_time;
      q.water = (water_mass_out - last_water_mass) / (water_density * dt);
      q.soil = (soil_mass_out - last_soil_mass) / (soil_density * dt);
    }
    if (q.water > peak_water_discharge) peak_water_discharge = q.water, peak_time = t;
    last_time = t, last_water_mass = water_mass_out, last_soil_mass = soil_mass_out;
    return q;
  }
};

}  // namespace suite::mpm2grid
