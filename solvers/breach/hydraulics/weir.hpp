#pragma once
// Discharge through a trapezoidal control section at critical flow (a broad-crested weir),
// the breach and crest outflow law of docs/methods/breach.md, from the DAMBRK/BREACH form
// (Fread 1988, NWS BREACH): with energy head h above the section invert (m), bottom width b (m),
// side slopes s (horizontal per vertical) and gravity g (m/s^2),
//   Q = c1 b h^1.5 + c2 s h^2.5,  c1 = (2/3)^1.5 sqrt(g),  c2 = (4/5)^2.5 sqrt(g/2)
// (c1 = 1.705, c2 = 1.268 in SI for g = 9.81). Each term is exact critical flow for its limit:
// c1 for a rectangle (critical depth 2/3 h), c2 for a triangle (critical depth 4/5 h); for a
// trapezoid the law adds the two limits. Free outflow only (no submergence).
namespace suite::breach {

// Q (m^3/s) by the two-term law; 0 for h <= 0.
double weir_discharge(double bottom_width, double side_slope, double head, double gravity);

// Exact critical-flow discharge of the same trapezoid: the depth y in (0, h) where the
// specific energy y + A / (2 T) equals h (A = b y + s y^2, T = b + 2 s y), then
// Q = sqrt(g A^3 / T). Solved by bisection to round-off; used to check the weir law.
double critical_discharge(double bottom_width, double side_slope, double head, double gravity);

}  // namespace suite::breach
