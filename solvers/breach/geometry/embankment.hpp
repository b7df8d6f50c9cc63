#pragma once
// A homogeneous trapezoidal embankment on a flat foundation, as WinDAM C and the dissertation's
// scenes describe it. Levels in m on the reservoir's datum; slopes are horizontal per vertical
// (H:V; the dissertation's Table 3.4 gives V:H, so 0.8333 V:H is 1.2 H:V).
//
// Streamwise coordinate x (m) runs upstream from the downstream toe: the downstream face spans
// [0, x_crest_downstream], the crest [x_crest_downstream, x_crest_upstream], then the upstream face.
//
// Scene form (section `dam`):
//   height: 12 m, crest_width: 6 m, crest_length: 150 m,
//   upstream_slope: 3, downstream_slope: 3, foundation: 0 m
#include "core/config/config.hpp"

namespace suite::breach {

struct Embankment {
  double height = 0.0;            // crest above foundation
  double crest_width = 0.0;       // streamwise
  double crest_length = 0.0;      // across the valley: the widest the breach can become
  double upstream_slope = 0.0;    // H:V
  double downstream_slope = 0.0;  // H:V
  double foundation = 0.0;        // level of the foundation (the breach stops there)

  static Embankment read(const config::Section& section);

  double crest() const { return foundation + height; }
  double x_crest_downstream() const { return downstream_slope * height; }
  double x_crest_upstream() const { return x_crest_downstream() + crest_width; }
  // Level of the embankment surface at x (foundation outside the embankment).
  double surface(double x) const;
  // Streamwise extent of the embankment at level z (base width at the foundation, crest width
  // at the crest, 0 above it).
  double streamwise_length(double z) const;
  // Slope length of the downstream face.
  double downstream_face_length() const;
  // Volume of a trapezoidal cut through the whole embankment: bottom width b at level z_b,
  // side slopes s (H:V), up to the crest, its width limited to the crest length (the cut stops
  // at the abutments). Exact (the integrand is piecewise polynomial in z).
  double cut_volume(double bottom_width, double side_slope, double invert) const;
};

}  // namespace suite::breach
